"""Writing into the report's folder without following a link below it: report.md and
plots/ are reached from the folder's descriptor (the folder itself may be a link: a
results disk), a link where the report writes is refused by name, and every file is
written as NAME.tmp.PID, fsynced, then renamed over NAME."""
import os

from .loading import die


def refuse_link(dir_fd, name, shown):
    """die() when `name` (relative to dir_fd) is a symbolic link; `shown` names it."""
    try:
        st = os.stat(name, dir_fd=dir_fd, follow_symlinks=False)
    except FileNotFoundError:
        return
    except OSError as e:
        die(f"{shown}: {e.strerror or e}")
    if (st.st_mode & 0o170000) == 0o120000:
        try:
            to = os.readlink(name, dir_fd=dir_fd)
        except OSError:
            to = "?"
        die(f"{shown} is a symbolic link (to {to}): shadesweep report never writes through "
            "a link below its output folder; remove the link, or give the folder it leads "
            "to as -o")


def open_dir(path):
    """A descriptor of the report's folder (following a link to it: that is the user's
    choice of folder)."""
    try:
        return os.open(path, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    except OSError as e:
        die(f"{path}: cannot open the folder: {e.strerror or e}")


def open_subdir(dir_fd, name, shown, create):
    """name below dir_fd as a descriptor, never through a link (None when it is absent
    and create is False)."""
    refuse_link(dir_fd, name, shown)
    if create:
        try:
            os.mkdir(name, dir_fd=dir_fd)
        except FileExistsError:
            pass
        except OSError as e:
            die(f"{shown}: cannot make the folder: {e.strerror or e}")
    try:
        return os.open(name, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC,
                       dir_fd=dir_fd)
    except FileNotFoundError:
        if create:
            die(f"{shown}: vanished while the report was written")
        return None
    except OSError as e:
        die(f"{shown}: not a folder the report can write into ({e.strerror or e})")


def write_atomic(dir_fd, name, data, shown):
    """data (bytes) as dir_fd/name: NAME.tmp.PID, fsync, rename; never through a link."""
    refuse_link(dir_fd, name, shown)
    tmp = f"{name}.tmp.{os.getpid()}"
    fd = -1
    try:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC,
                     0o666, dir_fd=dir_fd)
        view = memoryview(data)
        while view:
            n = os.write(fd, view)
            view = view[n:]
        os.fsync(fd)
        os.close(fd)
        fd = -1
        os.replace(tmp, name, src_dir_fd=dir_fd, dst_dir_fd=dir_fd)
    except OSError as e:
        if fd >= 0:
            os.close(fd)
        try:
            os.unlink(tmp, dir_fd=dir_fd)
        except OSError:
            pass
        die(f"{shown}: cannot write: {e.strerror or e}")


def remove(dir_fd, name):
    """Removes dir_fd/name when it is there (a link as a link: unlink never follows)."""
    try:
        os.unlink(name, dir_fd=dir_fd)
    except OSError:
        pass
