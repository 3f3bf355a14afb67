"""Checks the README and the pages of docs/ for what a newcomer relies on: a README of at most
120 lines whose Quick start holds the two commands (the first installs the packages the second's
script installs, less the formatters), a map naming every page of docs/, and every page a doc
names in backticks existing (but
those beside the repository, ../, and those a run writes, DIR/ and out/).

Usage: check_docs.py SOURCE_DIR
"""

import os
import re
import sys

MAX_README_LINES = 120


def sh_blocks(text):
    """The bodies of the sh blocks after the '## Quick start' heading, up to the next '## '."""
    section = text.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```sh\n(.*?)```", section, re.S)


def main():
    root = sys.argv[1]
    problems = []
    readme = open(os.path.join(root, "README.md"), encoding="utf-8").read()
    lines = readme.count("\n")
    if lines > MAX_README_LINES:
        problems.append("README.md has %d lines, more than %d" % (lines, MAX_README_LINES))
    blocks = sh_blocks(readme)
    if len(blocks) != 2:
        problems.append("README.md's Quick start holds %d sh blocks, not 2" % len(blocks))
    else:
        script = blocks[1].strip()
        if script != "bash tests/run_all.sh":
            problems.append("README.md's test command is '%s'" % script)
        installed = open(os.path.join(root, "tests", "run_all.sh"), encoding="utf-8").read()
        listed = re.search(r"--no-install-recommends (.*?) &&", blocks[0])
        if not listed:
            problems.append("README.md's first command installs no packages")
        else:
            for package in listed.group(1).split():
                if not re.search(r"(\s|\\)%s(\s|\\)" % re.escape(package), installed):
                    problems.append(
                        "package %s of the first command is not in tests/run_all.sh" % package
                    )
    pages = []
    for folder in ("docs", os.path.join("docs", "paper")):
        pages += [
            os.path.join(folder, name)
            for name in sorted(os.listdir(os.path.join(root, folder)))
            if name.endswith(".md")
        ]
    documentation = readme.split("## Documentation", 1)[-1].split("\n## ", 1)[0]
    for page in pages:
        if "`%s`" % page not in documentation:
            problems.append("README.md's Documentation does not name %s" % page)
    for document in ["README.md"] + pages:
        text = open(os.path.join(root, document), encoding="utf-8").read()
        here = os.path.dirname(document)
        for number, line in enumerate(text.splitlines(), 1):
            for name in re.findall(r"`((?:[\w.-]+/)*[\w.-]+\.md)`", line):
                if name.startswith(("../", "DIR/", "out/")):
                    continue  # beside the repository, or what a run writes
                candidates = [name, os.path.join("docs", name), os.path.join(here, name)]
                if not any(os.path.isfile(os.path.join(root, c)) for c in candidates):
                    problems.append(
                        "%s:%d: names %s, which does not exist" % (document, number, name)
                    )
    for problem in problems:
        print(problem)
    print(
        "README.md: %d lines; %d pages of docs/ checked; %d problems"
        % (lines, len(pages), len(problems))
    )
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
