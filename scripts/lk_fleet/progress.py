"""Progress of a run on stderr: done / running / failed counts, rate and time left, as a redrawn bar on a
terminal or a plain line every few seconds otherwise.

Depends on nothing of the package."""
import math
import sys
import time


class Progress:
    """Done / running / failed counts, rate and time left, on stderr: a redrawn bar on a terminal, a plain
    line every `interval` seconds otherwise (CI logs, files)."""

    def __init__(self, total, skipped, stream=sys.stderr, interval=5.0):
        self.total, self.skipped, self.stream = total, skipped, stream
        self.tty = stream.isatty()
        self.interval = 0.5 if self.tty else interval
        self.start = time.monotonic()
        self.last = -math.inf
        self.width = 0
        self.shown = ""

    def line(self, done, failed, running):
        ran = done - self.skipped
        elapsed = time.monotonic() - self.start
        rate = ran / elapsed * 60 if elapsed > 0 else 0.0
        left = self.total - done
        eta = duration(left / (rate / 60)) if ran and left else ("0 s" if not left else "?")
        counts = (f"{done}/{self.total} done ({self.skipped} skipped), {running} running, {failed} failed, "
                  f"{rate:.1f}/min, {eta} left")
        if not self.tty:
            return f"[lk_fleet] {counts}"
        filled = int(30 * done / self.total) if self.total else 30
        return f"[{'#' * filled}{'.' * (30 - filled)}] {counts}"

    def update(self, done, failed, running, force=False):
        now = time.monotonic()
        if not force and now - self.last < self.interval:
            return
        self.last = now
        text = self.line(done, failed, running())
        if text == self.shown:
            return
        self.shown = text
        if self.tty:
            self.stream.write("\r" + text.ljust(self.width))
            self.width = len(text)
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def note(self, text):
        """A line (a failed task) printed above the bar."""
        if self.tty and self.width:
            self.stream.write("\r" + " " * self.width + "\r")
            self.width = 0
        self.stream.write(text + "\n")
        self.stream.flush()
        self.last, self.shown = -math.inf, ""

    def finish(self, done, failed):
        self.update(done, failed, lambda: 0, force=True)
        if self.tty:
            self.stream.write("\n")


def duration(seconds):
    """'42 s', '7 min 05 s', '3 h 12 min'."""
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds} s"
    if seconds < 3600:
        return f"{seconds // 60} min {seconds % 60:02d} s"
    return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"
