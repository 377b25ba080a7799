"""What a submission is: which labs it holds and the bytes of its student files, read once,
never through a symbolic link.

Trust: reads untrusted files (regular files only, size-capped)."""
import os
import stat

from .common import MAX_STUDENT_FILE, BadInput, Defect
from .project import known_labs, student_files

# ------------------------------------------------------------ the submission

def _entries(path):
    return sorted(e for e in os.listdir(path) if not e.startswith(".") and e != "__MACOSX")


def _is_dir(p):
    """A real folder (a symbolic link to one is not followed)."""
    return os.path.isdir(p) and not os.path.islink(p)


def _is_file(p):
    """A real regular file (a symbolic link to one is not followed)."""
    try:
        return stat.S_ISREG(os.lstat(p).st_mode)
    except OSError:
        return False


def read_regular(p):
    """The bytes of a regular file, never through a symbolic link (or None)."""
    try:
        fd = os.open(p, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return None
    with os.fdopen(fd, "rb") as f:
        st = os.fstat(f.fileno())
        if not stat.S_ISREG(st.st_mode) or st.st_size > MAX_STUDENT_FILE:
            return None
        return f.read(MAX_STUDENT_FILE + 1)


def resolve_submission(repo, submission, lab_args):
    """Finds which labs to grade and the submitted student files.

    Returns (labs, overlays {lab: {name: bytes}}, notes {lab: [str]}, refused {lab: reason}).
    Symbolic links are never followed: a student file that is not a regular
    file is refused (its lab scores 0), a linked folder is not looked into."""
    known = known_labs(repo)
    if not known:
        raise Defect("no lab has graded tests (labs/<lab>/ with tests/<lab>/*.cpp)")
    for lab in lab_args:
        if lab not in known:
            raise BadInput(f"--lab {lab}: unknown lab (known: {', '.join(known)})")
    if not _is_dir(submission):
        raise BadInput(f"{submission}: no such folder (expected a folder laid out like labs/ "
                       "or one lab's folder)")

    def lab_dirs(path):
        return [l for l in known if _is_dir(os.path.join(path, l))]

    def cpp_files(path):
        return [e for e in _entries(path) if e.endswith(".cpp") and os.path.lexists(os.path.join(path, e))]

    # Look through wrapper folders: a lone subfolder, or a repository's labs/.
    path = submission
    for _ in range(3):
        if lab_dirs(path) or cpp_files(path):
            break
        entries = _entries(path)
        if _is_dir(os.path.join(path, "labs")):
            path = os.path.join(path, "labs")
        elif len(entries) == 1 and _is_dir(os.path.join(path, entries[0])):
            path = os.path.join(path, entries[0])
        else:
            break

    folders = {}
    if lab_dirs(path):
        labs = [l for l in known if l in lab_args] if lab_args else lab_dirs(path)
        for lab in labs:
            folders[lab] = os.path.join(path, lab)
    else:
        cpps = cpp_files(path)
        if len(lab_args) > 1:
            raise BadInput(f"{submission}: one lab's folder (no lab subfolders) but {len(lab_args)} "
                           "--lab flags: give one --lab")
        if lab_args:
            lab = lab_args[0]
        else:
            matches = {l: len(set(cpps) & set(student_files(repo, l))) for l in known}
            best = max(matches.values())
            winners = [l for l in known if matches[l] == best]
            if best == 0:
                raise BadInput(f"{submission}: no lab recognised: expected lab subfolders "
                               f"({', '.join(l + '/' for l in known)}) or one lab's .cpp files "
                               f"(e.g. {', '.join(student_files(repo, known[0])[:3])})")
            if len(winners) > 1:
                raise BadInput(f"{submission}: the .cpp files match labs {' and '.join(winners)} "
                               "equally: choose one with --lab")
            lab = winners[0]
        labs = [lab]
        folders[lab] = path

    overlays, notes, refused = {}, {}, {}
    for lab in labs:
        overlays[lab], notes[lab], refused[lab] = {}, [], ""
        folder = folders[lab]
        names = student_files(repo, lab)
        if os.path.islink(folder):
            refused[lab] = f"{lab}/ is a symbolic link, not a folder: refused"
            continue
        if not _is_dir(folder):
            notes[lab].append(f"no {lab}/ folder in the submission: every file keeps the skeleton")
            continue
        missing, extra = [], []
        for name in names:
            p = os.path.join(folder, name)
            if not os.path.lexists(p):
                missing.append(name)
            elif not _is_file(p):
                refused[lab] = refused[lab] or (f"{name} is not a regular file (a symbolic link, "
                                                "a folder or a device): refused")
            elif os.lstat(p).st_size > MAX_STUDENT_FILE:
                notes[lab].append(f"{name} is larger than {MAX_STUDENT_FILE // 1024} KiB: the skeleton is used")
            else:
                data = read_regular(p)
                if data is None:
                    refused[lab] = refused[lab] or f"{name} could not be read as a regular file: refused"
                else:
                    overlays[lab][name] = data
        for e in _entries(folder):
            pristine = os.path.join(repo, "labs", lab, e)
            if e in names:
                continue
            if os.path.isfile(pristine) and _is_file(os.path.join(folder, e)):
                with open(pristine, "rb") as a:
                    if a.read() != read_regular(os.path.join(folder, e)):
                        notes[lab].append(f"{e} differs from the pristine one and is ignored "
                                          "(headers are never edited: the pristine one is used)")
                continue
            extra.append(e)
        if missing:
            notes[lab].append(f"missing from the submission, the skeleton is used: {', '.join(missing)}")
        if extra:
            shown = ", ".join(extra[:8]) + (f" and {len(extra) - 8} more" if len(extra) > 8 else "")
            notes[lab].append(f"ignored (only labs/{lab}/*.cpp files are graded): {shown}")
    return labs, overlays, notes, refused


