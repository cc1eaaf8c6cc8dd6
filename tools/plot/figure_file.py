"""Figures written as tessera writes its files (docs/reliability.md): whole or not at all.

A figure is drawn under a temporary name beside its target, .tmp-<pid>@<host>@<name> (the form of
tessera's own temporaries, <host> 8 hex digits of the machine name's FNV-1a digest, so the next
tessera write into the folder removes a killed drawing's), synced, and renamed over the target. A
figure that cannot be written (a full disk) leaves the previous file as it was and ends the script
with one line on stderr and exit status 2.
"""
import os
import socket
import sys


def _host():
    digest = 14695981039346656037  # FNV-1a, 64 bit (io/file_digest.cpp)
    for byte in (socket.gethostname() or "localhost").encode():
        digest = ((digest ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return f"{digest:016x}"[:8]


def _reason(error):
    if error.errno in (28, 122, 27):  # ENOSPC, EDQUOT, EFBIG
        return f"disk full or over quota ({error.strerror}); free some space and draw it again"
    return error.strerror or str(error)


def save_figure(figure, path):
    """figure.savefig(path), whole or not at all; exits 2 naming the file when it cannot be written."""
    directory, name = os.path.split(os.path.abspath(path))
    temporary = os.path.join(directory, f".tmp-{os.getpid()}@{_host()}@{name}")
    try:
        figure.savefig(temporary, format=os.path.splitext(name)[1][1:])
        with open(temporary, "rb") as written:
            os.fsync(written.fileno())
        os.replace(temporary, path)
    except OSError as error:
        try:
            os.remove(temporary)
        except OSError:
            pass
        sys.stderr.write(f"{path}: cannot write: {_reason(error)}\n")
        sys.exit(2)
