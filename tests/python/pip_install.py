"""`pip install .` as a venv user does it, then the package from the venv
alone (ctest python.pip_install):

  1. a fresh venv (Debian's numpy and torch from the system's packages),
     pip install --no-build-isolation --no-index SOURCE: offline;
  2. import vkfuse from the venv (never the build tree) and run
     examples/python/*.py with it;
  3. the type stubs: mypy on the examples against the installed package,
     mypy.stubtest of the compiled module's stub against the module, and
     each stubbed function's parameters against the module's own signature.

    python3 pip_install.py SOURCE WORK [BUILD]

BUILD: build the module there (VKFUSE_BUILD_DIR: the test reuses the
tree's build, so it costs seconds; without it pip builds from scratch in a
temporary directory, minutes).
"""
import ast
import os
import shutil
import subprocess
import sys

def run(*cmd, **kw):
    print("+", " ".join(cmd), flush=True)
    return subprocess.run(cmd, check=True, **kw)


def top_level_split(text):
    """text split at the commas outside brackets and quotes."""
    parts, depth, quote, start = [], 0, None, 0
    for i, c in enumerate(text):
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    return parts + [text[start:]]


def stub_parameters_match(stub_path):
    """Every def in the stub names the parameters the compiled module's signature line does."""
    import importlib
    module = importlib.import_module("vkfuse._vkfuse")
    tree = ast.parse(open(stub_path, encoding="utf-8").read())
    problems = []

    def check(name, node, runtime):
        doc = (getattr(runtime, "__doc__", None) or "").splitlines()
        line = next((d for d in doc if d.startswith(node.name + "(")), None)
        if line is None:
            return  # properties and plain attributes carry no signature line
        given = [a.split(":")[0].strip() for a in top_level_split(line[len(node.name) + 1:line.rindex(") ->")]) if a]
        stubbed = [a.arg for a in node.args.args]
        if given != stubbed:
            problems.append(f"{name}: the stub has {stubbed}, the module {given}")

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            check(node.name, node, getattr(module, node.name))
        elif isinstance(node, ast.ClassDef):
            cls = getattr(module, node.name)
            for member in node.body:
                if isinstance(member, ast.FunctionDef) and not member.decorator_list:
                    check(f"{node.name}.{member.name}", member, getattr(cls, member.name))
    return problems


def main():
    SOURCE, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    BUILD = os.path.abspath(sys.argv[3]) if len(sys.argv) > 3 else None
    VENV = os.path.join(WORK, "venv")
    PY = os.path.join(VENV, "bin", "python")
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    run(sys.executable, "-m", "venv", "--system-site-packages", VENV)
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    if BUILD:
        env["VKFUSE_BUILD_DIR"] = BUILD
    run(os.path.join(VENV, "bin", "pip"), "install", "--no-build-isolation", "--no-index", "--quiet", SOURCE,
        env=env, cwd=WORK)
    where = subprocess.run([PY, "-c", "import vkfuse; print(vkfuse.__file__)"], env=env, cwd=WORK, check=True,
                           capture_output=True, text=True).stdout.strip()
    if not where.startswith(VENV + os.sep):
        sys.exit(f"vkfuse was imported from {where}, not the venv")
    examples = sorted(os.path.join(SOURCE, "examples", "python", f)
                      for f in os.listdir(os.path.join(SOURCE, "examples", "python")) if f.endswith(".py"))
    for example in examples:
        run(PY, example, env=env, cwd=WORK)
    run(PY, "-m", "mypy", "--config-file", os.path.join(SOURCE, "pyproject.toml"), "--cache-dir",
        os.path.join(WORK, "mypy"), *examples, env=env, cwd=WORK)
    # pybind11 classes have their own metaclass, which no stub can spell, and
    # one without a constructor (DeviceTensor: plans make them) a generic one.
    allow = os.path.join(WORK, "stubtest.allow")
    with open(allow, "w", encoding="utf-8") as f:
        f.write("vkfuse\\._vkfuse\\.[A-Za-z]+$\nvkfuse\\._vkfuse\\.DeviceTensor\\.__init__$\n")
    run(PY, "-m", "mypy.stubtest", "--allowlist", allow, "--mypy-config-file",
        os.path.join(SOURCE, "pyproject.toml"), "vkfuse._vkfuse", env=env, cwd=WORK)
    stub = os.path.join(os.path.dirname(where), "_vkfuse.pyi")
    problems = subprocess.run([PY, "-c", f"import sys; sys.path.insert(0, {os.path.dirname(__file__)!r}); "
                               f"import pip_install as p; print('\\n'.join(p.stub_parameters_match({stub!r})))"],
                              env=env, cwd=WORK, check=True, capture_output=True, text=True).stdout.strip()
    if problems:
        sys.exit(problems)
    print("pip install, examples and stubs: ok")


if __name__ == "__main__":
    main()
