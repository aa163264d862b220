"""Reading a user's input file (a saved page, a catalog CSV, a file of descriptions) with a size cap.

Only regular files are read: a device (``/dev/zero``), a named pipe or a socket never ends, so it would grow
the process until the machine ran out of memory, whatever size ``stat`` reports for it. Reading stops one
byte past the cap, so a file that grows while it is read cannot get around it either. Refusals are
:class:`OSError` with the reason as ``strerror``, which every caller already turns into its own one-line
error naming the file.
"""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

__all__ = ["read_input_file"]


def read_input_file(path: str | Path, max_bytes: int) -> bytes:
    """The bytes of the regular file at ``path``, refused when it is not one or holds over ``max_bytes``."""
    mode = os.stat(path).st_mode  # follows symlinks: a link to a regular file is fine
    if not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):  # a directory fails below with its own message
        raise OSError(errno.EINVAL, "not a regular file (a device, a pipe or a socket is never read)")
    with open(path, "rb") as fh:
        data = fh.read(max_bytes + 1)
    if len(data) > max_bytes:
        raise OSError(errno.EFBIG, f"too large (over {max_bytes:,} bytes)")
    return data
