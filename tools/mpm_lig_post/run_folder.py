"""An output folder that one tool run writes, held to mpm_lig's rules (docs/running.md §1, §3):
one writer at a time (a lock held for the run's life), no name inside the folder that leads
outside it (a symbolic link where the tool writes is refused), and files committed atomically
with their digests so that a resume can check what it continues from."""
import fcntl
import hashlib
import json
import os
import stat

from mpm_lig_post.errors import InputError


def refuse_links(folder, names):
    """InputError when one of `names` inside `folder` is a symbolic link or not a regular file
    (a folder for a name ending in '/'): nothing is read or written through it."""
    for name in names:
        path = os.path.join(folder, name.rstrip("/"))
        try:
            mode = os.lstat(path).st_mode
        except FileNotFoundError:
            continue
        wanted = stat.S_ISDIR if name.endswith("/") else stat.S_ISREG
        if stat.S_ISLNK(mode) or not wanted(mode):
            kind = "a symbolic link" if stat.S_ISLNK(mode) else "not a regular " + \
                ("folder" if name.endswith("/") else "file")
            raise InputError(f"{path}: is {kind}; the run writes only its own files inside "
                             "its output folder (remove it)")


def refuse_links_below(folder):
    """refuse_links for every entry of `folder` and of its sub-folders."""
    for entry in os.scandir(folder):
        real_folder = entry.is_dir(follow_symlinks=False)
        refuse_links(folder, [entry.name + ("/" if real_folder else "")])
        if real_folder:
            refuse_links_below(entry.path)


class FolderLock:
    """An exclusive lock on `folder` for this process's life: a second run into the same folder
    is refused (InputError naming the holder) and nothing of the first run is touched. The
    lock is the kernel's (flock): a run that died leaves a file any later run can take."""

    def __init__(self, folder, name):
        path = os.path.join(folder, name)
        refuse_links(folder, [name])
        self.fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.read(self.fd, 64).decode(errors="replace").strip() or "?"
            os.close(self.fd)
            raise InputError(f"{folder}: another run (pid {holder}) is writing this folder; "
                             "one run at a time") from None
        os.ftruncate(self.fd, 0)
        os.write(self.fd, f"{os.getpid()}\n".encode())

    def release(self):
        if self.fd is not None:
            os.close(self.fd)
            self.fd = None


def digest(path, length=None):
    """{'bytes': n, 'sha256': hex} of the file's first `length` bytes (all by default)."""
    h = hashlib.sha256()
    size = os.path.getsize(path) if length is None else length
    left = size
    with open(path, "rb") as f:
        while left > 0:
            block = f.read(min(left, 1 << 20))
            if not block:
                break
            h.update(block)
            left -= len(block)
    if left:
        raise InputError(f"{path}: shorter ({size - left} bytes) than the {size} it must have")
    return {"bytes": size, "sha256": h.hexdigest()}


def check_digest(folder, name, expected, prefix=False):
    """InputError naming the file when it is missing, shorter, or its content (its first
    expected['bytes'] bytes with `prefix`) differs from `expected`."""
    path = os.path.join(folder, name)
    if not os.path.isfile(path):
        raise InputError(f"{path}: missing; the checkpoint needs it")
    size = os.path.getsize(path)
    if size < expected["bytes"] or (size != expected["bytes"] and not prefix):
        raise InputError(f"{path}: {size} bytes, the checkpoint recorded {expected['bytes']}: "
                         "damaged or replaced")
    if digest(path, expected["bytes"])["sha256"] != expected["sha256"]:
        raise InputError(f"{path}: its content differs from the checkpoint's digest: damaged or "
                         "replaced")


def write_json_atomic(path, data):
    """`path` replaced at once by the JSON of `data` (flushed to disk before the rename)."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)
