"""Files that are whole or absent: atomic writes (temporary file, fsync, rename, fsync of the directory), CSV
text, and the publication of a finished attempt's folder under its final name. Everything lk_fleet writes
goes through here, so a crash (or a rerun after one) never finds a torn file.

Depends on nothing of the package."""
import csv
import io
import json
import os
import shutil
import tempfile


def write_bytes_atomic(path, data):
    """Write, fsync and rename in the same directory: a reader (or a rerun after a crash) sees the old
    file or the complete new one, never a torn one."""
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".tmp-" + os.path.basename(path) + ".", dir=directory)
    try:
        os.fchmod(fd, 0o644)  # mkstemp makes 0600; the results are for everyone who reads the report
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    # The rename itself is durable only once the directory entry is on disk.
    dir_fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def write_json_atomic(path, obj):
    write_bytes_atomic(path, (json.dumps(obj, indent=1, sort_keys=True) + "\n").encode())


def write_text_atomic(path, text):
    write_bytes_atomic(path, text.encode())


def csv_text(header, rows):
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=header, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return buffer.getvalue()


def publish_dir(attempt_dir, final_dir):
    """Move an attempt's output to its final name. Each attempt writes to its own directory, so a retry
    never mixes files with an earlier attempt; a stale earlier copy is replaced."""
    if os.path.exists(final_dir):
        trash = tempfile.mkdtemp(prefix=".old-", dir=os.path.dirname(final_dir))
        os.rename(final_dir, os.path.join(trash, "x"))
        shutil.rmtree(trash, ignore_errors=True)
    os.rename(attempt_dir, final_dir)
    return final_dir
