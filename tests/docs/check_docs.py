#!/usr/bin/env python3
"""README.md and docs/*.md checked against the build they describe.

  check_docs.py SOURCE_DIR BUILD_DIR

- Every test label a `ctest -L ...` names exists in the build.
- Every `vkfuse::NAME` written as a target (the whole of a code span) is a
  CMake target the project declares.
- Every path of the repository a code span names (`src/vk/`, `tools/run/`,
  `docs/spec.md`) exists.
- Every `$ vkfuse ...` line of a code block runs offline and exits as the
  block shows (0 unless an `echo $?` line after it says otherwise), in a
  scratch folder that sees the repository's tests/ and examples/. A block
  whose info string says `example` (```text example) shows commands that need
  what a test host has not (a DIGIT, a ROS 2 host, minutes of work) and is
  only read.
- Dated measurements live in docs/measurements.md, each section naming the
  commit it was measured at (which must exist where the history is there);
  README.md and the other docs carry no date.

Prints one line per problem and exits 1 if there is any.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile

SOURCE, BUILD = sys.argv[1], sys.argv[2]
DOCS = ["README.md"] + sorted("docs/" + f for f in os.listdir(os.path.join(SOURCE, "docs")) if f.endswith(".md"))
problems = []


def problem(doc, line, what):
    problems.append(f"{doc}:{line}: {what}")


def read(doc):
    with open(os.path.join(SOURCE, doc), encoding="utf-8") as f:
        return f.read().split("\n")


def code_blocks(lines):
    """(first line number, info string, lines) of each fenced block."""
    block, info, start = None, "", 0
    for n, line in enumerate(lines, 1):
        fence = re.match(r"\s*```(.*)$", line)
        if fence and block is None:
            block, info, start = [], fence.group(1).strip(), n
        elif fence:
            yield start, info, block
            block = None
        elif block is not None:
            block.append(line)


def labels():
    out = subprocess.run(["ctest", "--print-labels"], cwd=BUILD, capture_output=True, text=True, check=True).stdout
    return {l.strip() for l in out.split("All Labels:")[-1].splitlines() if l.strip()}


def cmake_targets():
    names = set()
    for root, dirs, files in os.walk(SOURCE):
        dirs[:] = [d for d in dirs if not d.startswith(".") and not d.startswith("build")]
        for f in files:
            if f == "CMakeLists.txt" or f.endswith(".cmake") or f.endswith(".cmake.in"):
                with open(os.path.join(root, f), encoding="utf-8") as h:
                    names.update(re.findall(r"vkfuse::[a-z0-9_]+", h.read()))
    return names


def public_identifiers():
    """Identifiers the public headers declare: `vkfuse::open_backend` names a function, not a target."""
    names = set()
    for root, _, files in os.walk(os.path.join(SOURCE, "include")):
        for f in files:
            with open(os.path.join(root, f), encoding="utf-8") as h:
                names.update(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", h.read()))
    return names


def check_references(doc, lines, known_labels, known_targets, api_names):
    for n, line in enumerate(lines, 1):
        for spec in re.findall(r"ctest[^`]*?-L\s+([A-Za-z0-9_|]+)", line):
            for label in spec.split("|"):
                if label not in known_labels:
                    problem(doc, n, f"ctest label '{label}' does not exist (labels: {', '.join(sorted(known_labels))})")
        for path in re.findall(r"(?<![A-Za-z0-9_./-])((?:src|tools|tests|docs|bench|shaders|include|examples|python|ros2|fuzz|cmake)/[A-Za-z0-9_/.-]*\.(?:cpp|hpp|h|glsl|comp|sh|py|md|txt|cmake))\b", line):
            if not os.path.exists(os.path.join(SOURCE, path)):
                problem(doc, n, f"{path} names no file of the repository")
        for span in re.findall(r"`([^`]+)`", line):
            if re.fullmatch(r"vkfuse::[a-z0-9_]+", span) and span not in known_targets and \
                    span.split("::")[1] not in api_names:
                problem(doc, n, f"{span} is not a CMake target of the project")
            path = re.fullmatch(r"((?:src|tools|tests|docs|bench|shaders|include|examples|python|ros2|fuzz|cmake)/[A-Za-z0-9_./-]*)", span)
            if path and "*" not in span and "<" not in span and not os.path.exists(os.path.join(SOURCE, path.group(1))):
                problem(doc, n, f"`{span}` names no file or folder of the repository")


def run_commands(doc, lines, vkfuse):
    """Each block's commands in order, in one scratch folder (a later one reads what an earlier one wrote)."""
    for start, info, block in code_blocks(lines):
        if "example" in info.split():
            continue
        with tempfile.TemporaryDirectory() as scratch:
            for shared in ("tests", "examples"):
                os.symlink(os.path.join(SOURCE, shared), os.path.join(scratch, shared))
            os.makedirs(os.path.join(scratch, "out"))
            for i, line in enumerate(block):
                m = re.match(r"\s*\$ (vkfuse .*)$", line)
                if not m:
                    continue
                command, j = m.group(1), i
                while command.endswith("\\") and j + 1 < len(block):
                    j += 1
                    command = command[:-1] + " " + block[j].strip()
                command = re.sub(r"\s+#.*$", "", command)
                expected = 0
                for k in range(j + 1, len(block)):
                    if block[k].strip().startswith("$ vkfuse"):
                        break
                    if block[k].strip() == "$ echo $?" and k + 1 < len(block) and block[k + 1].strip().isdigit():
                        expected = int(block[k + 1].strip())
                        break
                try:
                    r = subprocess.run([vkfuse] + shlex.split(command)[1:], cwd=scratch, capture_output=True,
                                       text=True, timeout=120)
                    if r.returncode != expected:
                        last = (r.stderr.strip().splitlines() or [""])[-1]
                        problem(doc, start + 1 + i,
                                f"`{command}` exited {r.returncode}, the block shows {expected}: {last}")
                except subprocess.TimeoutExpired:
                    problem(doc, start + 1 + i, f"`{command}` ran past 120 s (mark its block `example`)")


def check_dates(doc, lines):
    dated = re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b")
    if doc == "docs/measurements.md":
        sections = []
        for n, line in enumerate(lines, 1):
            if line.startswith("## "):
                sections.append([n, line, False])
            elif sections and re.search(r"\bcommit [0-9a-f]{7,40}\b", line):
                sections[-1][2] = True
                for commit in re.findall(r"\bcommit ([0-9a-f]{7,40})\b", line):
                    if os.path.isdir(os.path.join(SOURCE, ".git")):
                        known = subprocess.run(["git", "cat-file", "-e", commit + "^{commit}"], cwd=SOURCE,
                                               capture_output=True).returncode == 0
                        if not known:
                            problem(doc, n, f"commit {commit} is not in the repository's history")
        for n, title, has_commit in sections:
            if not has_commit:
                problem(doc, n, f"'{title[3:]}' names no commit it was measured at")
        return
    for n, line in enumerate(lines, 1):
        if dated.search(line):
            problem(doc, n, "a dated measurement: it belongs in docs/measurements.md, with its commit")


def main():
    vkfuse = os.path.join(BUILD, "vkfuse")
    known_labels, known_targets, api_names = labels(), cmake_targets(), public_identifiers()
    for doc in DOCS:
        lines = read(doc)
        check_references(doc, lines, known_labels, known_targets, api_names)
        run_commands(doc, lines, vkfuse)
        check_dates(doc, lines)
    for p in problems:
        print(p)
    print(f"check_docs: {len(DOCS)} documents, {len(problems)} problems")
    return 1 if problems else 0


sys.exit(main())
