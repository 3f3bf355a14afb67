"""Runs the `sh` blocks of a Markdown page in order, in one shell, and checks each `output` block
against what the `sh` block before it printed: the same words, and every number within 2% (so a
page such as docs/tutorial.md cannot go stale).

Usage: run_doc_blocks.py PAGE.md BUILD_DIR WORK_DIR

The page's commands start in WORK_DIR, which holds `build` (a link to BUILD_DIR) as the
repository's root does; HOME is WORK_DIR too, so `~` stays inside it.
"""

import os
import re
import shutil
import subprocess
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
RELATIVE_TOLERANCE = 0.02


def fenced_blocks(text):
    """(info, body, line) of every fenced block, in order."""
    blocks, info, body, start = [], None, [], 0
    for number, line in enumerate(text.splitlines(), 1):
        if info is None and line.startswith("```"):
            info, body, start = line[3:].strip(), [], number
        elif info is not None and line.startswith("```"):
            blocks.append((info, "\n".join(body), start))
            info = None
        elif info is not None:
            body.append(line)
    if info is not None:
        sys.exit("unclosed fence opened at line %d" % start)
    return blocks


def split_numbers(text):
    """The text with each number replaced by '#', and the numbers."""
    numbers = [float(m) for m in NUMBER.findall(text)]
    return NUMBER.sub("#", text), numbers


def same_output(expected, actual):
    """None when actual matches expected, else why not."""
    want_words, got_words = expected.split(), actual.split()
    want_shape, want = split_numbers(" ".join(want_words))
    got_shape, got = split_numbers(" ".join(got_words))
    if want_shape != got_shape:
        return "the words differ:\n  expected: %s\n  printed:  %s" % (
            " ".join(want_words),
            " ".join(got_words),
        )
    for a, b in zip(want, got):
        if abs(a - b) > RELATIVE_TOLERANCE * max(abs(a), abs(b)):
            return "%g printed where the page says %g (beyond %g relative)" % (
                b,
                a,
                RELATIVE_TOLERANCE,
            )
    return None


def main():
    page, build, work = sys.argv[1:4]
    blocks = fenced_blocks(open(page, encoding="utf-8").read())
    commands = [(body, line) for info, body, line in blocks if info == "sh"]
    if not commands:
        sys.exit("%s: no sh block" % page)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.symlink(os.path.abspath(build), os.path.join(work, "build"))
    marker = "@@block@@"
    script = ["set -euo pipefail"]
    for body, line in commands:
        script += ["echo %s%d" % (marker, line), body]
    env = dict(os.environ, HOME=work)
    run = subprocess.run(
        ["bash", "-c", "\n".join(script)],
        cwd=work,
        env=env,
        stdout=subprocess.PIPE,
        text=True,
    )
    printed = {}
    current = None
    for out_line in run.stdout.splitlines():
        if out_line.startswith(marker):
            current = int(out_line[len(marker) :])
            printed[current] = []
        elif current is not None:
            printed[current].append(out_line)
    if run.returncode != 0:
        last = max(printed) if printed else commands[0][1]
        sys.exit(
            "%s: the sh block at line %d failed (exit code %d); it printed:\n%s"
            % (page, last, run.returncode, "\n".join(printed.get(last, [])))
        )
    failures = 0
    previous = None
    for info, body, line in blocks:
        if info == "sh":
            previous = line
        elif info == "output":
            if previous is None:
                sys.exit("%s:%d: an output block before any sh block" % (page, line))
            why = same_output(body, "\n".join(printed.get(previous, [])))
            if why:
                failures += 1
                print(
                    "%s:%d: the output of the sh block at line %d: %s" % (page, line, previous, why)
                )
    checked = sum(1 for info, _, _ in blocks if info == "output")
    print(
        "%d sh blocks ran, %d output blocks checked, %d differ" % (len(commands), checked, failures)
    )
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
