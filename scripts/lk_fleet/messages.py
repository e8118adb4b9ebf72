"""What lk_fleet tells its user outside the reports: status lines on stderr, and UsageError, a bad argument
(reported by the command line, exit status 2).

Depends on nothing of the package; any module may use it."""
import sys


class UsageError(Exception):
    """Bad command-line input: reported as 'argument NAME: message', exit status 2."""

    def __init__(self, argument, message):
        super().__init__(f"argument {argument}: {message}")


def status(text):
    """Messages and progress go to stderr: stdout stays free for a caller's pipe."""
    print(f"[lk_fleet] {text}", file=sys.stderr, flush=True)
