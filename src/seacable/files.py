"""Where seacable writes, and what it reads of files it did not write: one check of every
output path a command is given, one way to write a file so that nothing but that file changes,
and one check that an HDF5 file holds its own data.

``check_output`` refuses an output that is a link (written through, it would replace the file
it points to), a directory, a file the command reads (a case, its tables, meshes, databases),
a name of another kind (``-o case.yaml`` for a picture), an existing file that is not an
output of the same kind (a hydrodynamic database given as a run's output), a folder that does
not exist or cannot be written, and a results file another run is writing. ``replacing`` and
``replace_text`` write under a name nobody else can take (a private folder, or a file created
exclusively), then move the result into place: a link planted at a predictable temporary name
cannot redirect the write, and an interrupted write leaves the previous file whole."""

import contextlib
import csv
import io
import os
import shutil
import tempfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import h5py
import yaml

from seacable.errors import InputError, OutputError

HDF5 = b"\x89HDF\r\n\x1a\n"  # an HDF5 file's signature (NetCDF-4's too)
HEAD = 4096  # the bytes read of an existing file to tell its kind
HYDRODB = "seacable hydrodynamic database"  # the title of a database seacable writes
GENERATOR = '<meta name="generator" content="seacable report">'  # in a page it may replace


def _head(path: Path) -> bytes:
    with path.open("rb") as f:
        return f.read(HEAD)


def _netcdf_title(path: Path) -> str | None:
    """The ``title`` attribute of an HDF5/NetCDF-4 file, "" for one without, None for a file
    that is not HDF5 (or is locked by a writer: OutputError)."""
    if not _head(path).startswith(HDF5):
        return None
    try:
        with h5py.File(path, "r") as f:
            title = f.attrs.get("title", "")
    except OSError as exc:
        if "lock" in str(exc).lower():
            raise OutputError(
                f"output file '{path}' is being written by another run; wait for it to end or "
                "choose another output file"
            ) from None
        return None
        if not title and {"time_dependence", "matrices"} <= set(f.attrs):
            title = HYDRODB  # written before databases had a title
    return title.decode(errors="replace") if isinstance(title, bytes) else str(title)


def _picture(path: Path) -> bool:
    head = _head(path)
    return head.startswith((b"\x89PNG", b"%PDF", b"\xff\xd8\xff")) or b"<svg" in head


def _case_text(path: Path) -> bool:
    """A YAML case file: a mapping whose top keys include a case's."""
    if path.stat().st_size > 10_000_000:
        return False
    try:  # its nodes only: aliases are not expanded (a file of nested aliases stays small)
        root = yaml.compose(path.read_text(encoding="utf-8"), Loader=yaml.SafeLoader)
    except (yaml.YAMLError, UnicodeDecodeError, ValueError, RecursionError):
        return False
    if not isinstance(root, yaml.MappingNode):
        return False
    keys = {key.value for key, _ in root.value if isinstance(key, yaml.ScalarNode)}
    return bool({"lines", "bodies", "cables"} & keys)


@dataclass(frozen=True)
class Kind:
    """A kind of output: what it is called, the names it may take (the first suggested) and
    which existing file it may replace."""

    what: str
    suffixes: tuple[str, ...]
    replaces: Callable[[Path, str | None], bool]


KINDS = {
    "netcdf": Kind("NetCDF file", (".nc", ".nc4", ".h5", ".hdf5"),
                   lambda path, title: title is not None and _netcdf_title(path) == title),
    "zarr": Kind("Zarr store", (".zarr",), lambda path, title: False),
    "picture": Kind("picture", (".png", ".svg", ".pdf", ".jpg", ".jpeg"),
                    lambda path, title: _picture(path)),
    "animation": Kind("animation", (".gif",), lambda path, title: _head(path)[:4] == b"GIF8"),
    "page": Kind("seacable report", (".html", ".htm"),
                 lambda path, title: GENERATOR.encode() in _head(path)),
    "collection": Kind("ParaView collection", (".pvd",),
                       lambda path, title: b'<VTKFile type="Collection"' in _head(path)),
    "case": Kind("case file", (".yaml", ".yml"), lambda path, title: _case_text(path)),
}  # fmt: skip


def _same_file(path: Path, read) -> bool:
    read = Path(read)
    if path.resolve() == read.resolve():
        return True
    try:
        return path.exists() and read.exists() and os.path.samefile(path, read)
    except OSError:
        return False


def check_output(path, kind: str, inputs=(), title: str | None = None,
                 option: str = "output") -> Path:  # fmt: skip
    """``path`` as an output of ``kind`` (a key of ``KINDS``), or OutputError naming the
    option, the path, what is wrong and the fix. ``inputs``: the files the command reads;
    ``title``: the ``title`` attribute of the NetCDF file written (an existing one is replaced
    only if it has the same)."""
    path = Path(path)
    form = KINDS[kind]
    name = f"{option} '{path}'"
    if path.is_symlink():
        raise OutputError(
            f"{name} is a link (to '{os.readlink(path)}'); seacable does not write through "
            "links, which would replace the file linked to: give the file's own path"
        )
    if path.is_dir() and kind != "zarr":
        raise OutputError(f"{name} is a directory; give a file name ending in {form.suffixes[0]}")
    for read in inputs:
        if _same_file(path, read):
            raise OutputError(
                f"{name} is a file this command reads, which the output would replace; give "
                f"another file name ending in {form.suffixes[0]}"
            )
    if path.suffix.lower() not in form.suffixes:
        raise OutputError(
            f"{name}: the output is {_article(form.what)}, and '{path.suffix or path.name}' is "
            f"not one of its names ({', '.join(form.suffixes)}); give a name ending in "
            f"{form.suffixes[0]}"
        )
    if not path.parent.is_dir():
        raise OutputError(
            f"{name}: its folder '{path.parent}' does not exist; create it (mkdir -p) or "
            "choose another"
        )
    if not os.access(path.parent, os.W_OK):
        raise OutputError(f"{name}: its folder '{path.parent}' cannot be written; choose another")
    if path.exists() and not (path.is_dir() if kind == "zarr" else form.replaces(path, title)):
        what = f"a '{title}' file" if title else _article(form.what)
        raise OutputError(
            f"{name} exists and is not {what} (seacable replaces only an output of the same "
            "kind); remove it or choose another name"
        )
    if kind == "zarr" and path.is_dir() and not (path / ".zgroup").exists():
        raise OutputError(
            f"{name} exists and is not a Zarr store (seacable replaces only an "
            "output of the same kind); remove it or choose another name"
        )
    return path


def _article(what: str) -> str:
    return f"an {what}" if what[:1].lower() in "aeiou" else f"a {what}"


@contextlib.contextmanager
def replacing(path) -> Iterator[Path]:
    """A name to write ``path``'s new content under, in a private folder beside it (made with
    a random name, mode 0700: nobody can plant a link there); moved onto ``path`` when the
    block ends, thrown away if it raises. For writers that open files by name (HDF5,
    matplotlib, Zarr)."""
    path = Path(path)
    folder = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".writing", dir=path.parent))
    try:
        aside = folder / path.name
        yield aside
        if aside.is_dir() and path.is_dir():  # a Zarr store: the old one goes
            shutil.rmtree(path)
        os.replace(aside, path)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def replace_text(path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` through a file created exclusively beside it, then
    moved into place; the file gets the mode a new file gets (the umask's)."""
    path = Path(path)
    fd, aside = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".writing", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.chmod(aside, 0o666 & ~UMASK)
        os.replace(aside, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(aside)
        raise
    return path


def self_contained(path) -> None:
    """Refuse an HDF5/NetCDF-4 file that keeps data in other files (a dataset in external
    storage, a virtual dataset, an external link): opened, it would read those files, which
    can be any file on this machine. seacable writes none; InputError names the first. A file
    that is not HDF5 is left to its reader."""
    path = Path(path)
    if not path.is_file() or not _head(path).startswith(HDF5):
        return
    outside: list[str] = []

    def visit(name: str, link) -> None:
        if isinstance(link, h5py.ExternalLink):
            outside.append(f"'{name}' links to '{link.filename}'")
        elif isinstance(link, h5py.HardLink):
            item = f.get(name)
            if isinstance(item, h5py.Dataset) and (item.external or item.is_virtual):
                where = item.external[0][0] if item.external else "other files"
                outside.append(f"'{name}' is stored in {where!r}")

    try:
        with h5py.File(path, "r") as f:
            f.visititems_links(visit)
    except OSError as exc:
        raise InputError(f"'{path}' is not a readable NetCDF/HDF5 file ({exc}); give a file "
                         "that seacable wrote") from None  # fmt: skip
    if outside:
        raise InputError(
            f"'{path}': {outside[0]}; seacable reads only files that hold their own data "
            "(it writes no other kind): use the file seacable wrote"
        )


def regular_file(path, what: str, error: type[Exception] = InputError, give: str = "") -> Path:
    """``path`` if it is a regular file, else ``error`` with one line (``what``: "table file",
    "mesh file", ... as the messages name it; ``give``: the fix, after a semicolon): missing,
    a directory, or not a regular file (a device such as /dev/zero, a pipe: they may never
    end)."""
    path = Path(path)
    fix = f"; {give}" if give else ""
    if not path.exists():
        raise error(f"{what} '{path}' does not exist{fix}")
    if path.is_dir():
        raise error(f"{what} '{path}' is a directory{fix}")
    if not path.is_file():
        raise error(f"{what} '{path}' is not a regular file (a device, a pipe or a socket)"
                    f"{fix or '; give a file'}")  # fmt: skip
    return path


def read_bytes(path, what: str, limit: int, error: type[Exception] = InputError,
               give: str = "") -> bytes:  # fmt: skip
    """The bytes of the side file ``path`` (``regular_file``), never more than ``limit``;
    ``error`` (the reader's exception class) with one line for a file that cannot be read or
    is larger than ``limit``."""
    path = regular_file(path, what, error, give)
    try:
        with path.open("rb") as f:
            raw = f.read(limit + 1)
    except OSError as exc:
        raise error(f"{what} '{path}' cannot be read ({exc.strerror or exc})") from None
    if len(raw) > limit:
        raise error(f"{what} '{path}' is larger than {limit:,} bytes, more than any such file "
                    "holds")  # fmt: skip
    return raw


def read_text(path, what: str, limit: int, error: type[Exception] = InputError,
              fix: str = "save it as UTF-8", give: str = "") -> str:  # fmt: skip
    """The UTF-8 text of ``path`` (a byte-order mark dropped), read by ``read_bytes``; a
    file that is not UTF-8 is refused naming the byte and its position, and ``fix``."""
    raw = read_bytes(path, what, limit, error, give)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise error(
            f"{what} '{path}' is not UTF-8 text (byte {raw[exc.start]:#04x} at position "
            f"{exc.start}); {fix}"
        ) from None


UMASK = os.umask(0o022)  # the process's file-creation mask, read once (os.umask sets it)
os.umask(UMASK)
LONGEST_CELL = 1_000_000  # characters of a CSV cell (Python's csv stops at 131,072)


def quoted(text: str, most: int = 40) -> str:
    """``text`` in quotes for a message, cut in the middle when longer than ``most``
    characters (a cell of a table can hold 200,000)."""
    if len(text) <= most:
        return f"'{text}'"
    return f"'{text[: most // 2]}...{text[-8:]}' ({len(text):,} characters)"


def csv_rows(text: str, where: str, error: type[Exception] = InputError):
    """(line number, cells) of each row of CSV ``text`` that is not blank or a comment (its
    first cell starting with '#'); a row the csv module cannot read (a cell over
    LONGEST_CELL characters, a NUL) is ``error`` naming ``where`` and the line."""
    csv.field_size_limit(LONGEST_CELL)
    reader = csv.reader(io.StringIO(text))
    while True:
        try:
            cells = next(reader)
        except StopIteration:
            return
        except csv.Error as exc:
            raise error(f"{where} line {reader.line_num}: not readable CSV ({exc}); give cells "
                        "of numbers or words separated by commas") from None  # fmt: skip
        if cells and any(c.strip() for c in cells) and not cells[0].strip().startswith("#"):
            yield reader.line_num, cells
