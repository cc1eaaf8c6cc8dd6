"""Every project path named in the docs, comments and build files exists (docs that cannot drift).

Scans README.md and docs/**/*.md whole, and the comments of the project's sources, scripts and
CMake files (after `//` or `#`: code names files of runs and temporary folders), for names of the
form FOLDER/NAME with FOLDER one of the project's top-level folders, and fails listing each one
that names no file or folder, from the project's root or from the naming file's folder. A name
followed by a wildcard or braces (a pattern, `tests/fixtures/*.h`) is not checked.

Usage: /usr/bin/python3 tests/paths_exist.py SOURCE_DIR
"""
import os
import re
import sys

FOLDERS = ("geometry", "levelset", "solver", "run", "tools", "python", "io", "tests", "bench", "docs", "scripts",
           "assets", "fuzz", ".ci")
# A project path: a top-level folder, then folders and a file name with an extension, or a folder
# ending in "/". Not preceded by a character that would make it part of a longer path or a URL.
PATH = re.compile(r"(?<![\w./-])((?:%s)/[\w./-]*[\w/])(?![\w*{])" % "|".join(re.escape(f) for f in FOLDERS))
# A section of a document named after it: docs/physics.md, "Protocol" (or docs/physics.md "Protocol").
SECTION = re.compile(r"((?:docs/)?[\w/]+\.md),? \"([^\"]+)\"")
SCANNED = (".md", ".h", ".cpp", ".py", ".sh", ".txt", ".toml")
SKIPPED_DIRS = {"build", "out", ".git", "__pycache__"}


def scanned_files(root):
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if d not in SKIPPED_DIRS and not d.startswith("build")]
        for name in files:
            if name.endswith(SCANNED) or name == "run" and os.path.basename(folder) == ".ci":
                yield os.path.join(folder, name)


def checked_text(path, line):
    """The part of a line that names files for a reader: all of a document, a source's comment."""
    if path.endswith(".md"):
        return line
    marker = "//" if path.endswith((".h", ".cpp")) else "#"
    at = line.find(marker)
    return line[at:] if at >= 0 else ""


def named_paths(text):
    for match in PATH.finditer(text):
        path = match.group(1).rstrip(".")
        # A path inside another project (a quoted repository path, e.g. "TopoLite's
        # python/...") is written with its project's name before it, which the look-behind keeps
        # out; what remains is this project's.
        yield path


def headings(path):
    """A document's section titles: its # headings and the bold run-in titles that open a
    paragraph or a list item (**Contact evaluation** ...)."""
    titles = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                titles.append(line.lstrip("#").strip())
            bold = re.match(r"\s*(?:[-*] |\d+\. )?\*\*([^*]+)\*\*", line)
            if bold:
                titles.append(bold.group(1).strip().rstrip(".:"))
    return titles


def missing_section(root, here, document, section):
    """The reason a named section cannot be found, or None."""
    for base in (root, here, os.path.join(root, "docs")):
        path = os.path.join(base, document)
        if os.path.isfile(path):
            titles = headings(path)
            # The title itself, or its first words ("Contact kernel" for "Contact kernel, issue #17").
            if any(re.match(re.escape(section) + r"(\W|$)", t) for t in titles):
                return None
            return "no section \"%s\" in %s" % (section, document)
    return None  # the document itself is checked as a path


def main():
    root = os.path.abspath(sys.argv[1])
    missing = []
    for path in sorted(scanned_files(root)):
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
        here = os.path.dirname(path)
        for number, line in enumerate(lines, 1):
            for name in named_paths(checked_text(path, line)):
                if not os.path.exists(os.path.join(root, name)) and not os.path.exists(os.path.join(here, name)):
                    missing.append("%s:%d: no such file or folder: %s" % (os.path.relpath(path, root), number, name))
            for document, section in SECTION.findall(checked_text(path, line)):
                reason = missing_section(root, here, document, section)
                if reason:
                    missing.append("%s:%d: %s" % (os.path.relpath(path, root), number, reason))
    for m in missing:
        print("paths: " + m)
    if missing:
        print("paths: %d names of files or sections that do not exist; correct the name or the document" % len(missing))
        return 1
    print("paths: every project path named exists")
    return 0


if __name__ == "__main__":
    sys.exit(main())
