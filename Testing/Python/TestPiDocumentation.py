"""The documentation against the code, where a machine can tell (pvpython).

    pvpython TestPiDocumentation.py SOURCE_DIR [CXX_COMPILER INCLUDE_DIRS]

1. The user guide names every proxy and property of the plugin. For every proxy of
   every XML file under Plugin/ (Plugin/**/*.xml), except the groups `internal_*`
   (bases other proxies inherit from) and bare <Proxy group=... name=.../> listings,
   Documentation/user-guide.md must have a heading holding the proxy's pvpython name in
   backquotes (`PiSurface`) and its label (Pi Surface). Its section (down to the next
   heading of the same level or higher) must name each property of the proxy, inherited
   ones included, in backquotes (`Resolution`). Names, not labels: pvpython spells them
   so, and the XML's labels are derived from them.
2. The runnable examples run. Every ```python run block of README.md and of the pages
   of Documentation/ is executed (README.md and paraview-tutorial.md must have some),
   block after block in one namespace per file (a later block may use an earlier one's names), in a scratch folder whose
   Testing/ links to the source tree's (the examples name paths relative to the
   repository's root, as a user runs them). A block fails on an exception or on an
   ERROR that VTK reports while it runs; then every pipeline the page built is updated,
   and must report no ERROR either. Plain ```python blocks are shown, not run.
3. The ```cpp blocks of README.md compile (syntax and types, with the include folders
   CMake passes; not linked), when a compiler is given.

Each failure names the file and the line of the block, so a failing run says which page
drifted from which part of the code.
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import traceback

from pitesting import check, finish

SOURCE = os.path.abspath(sys.argv[1])
GUIDE = os.path.join(SOURCE, "Documentation", "user-guide.md")
README = os.path.join(SOURCE, "README.md")
TUTORIAL = os.path.join(SOURCE, "Documentation", "paraview-tutorial.md")
# Pages that must hold runnable blocks; any other page of Documentation/ may.
REQUIRED = [README, TUTORIAL]
RUNNABLE = REQUIRED + sorted(set(glob.glob(os.path.join(SOURCE, "Documentation", "*.md")))
                             - set(REQUIRED))


# --- 1. Every proxy and property in the user guide -------------------------------------

def load_proxies():
    """(group, name) -> proxy element, over every XML file under Plugin/ (the loader of
    Scripts/user_guide_tables.py, which prints the guide's tables)."""
    check(glob.glob(os.path.join(SOURCE, "Plugin", "**", "*.xml"), recursive=True),
          "no XML file under %s/Plugin" % SOURCE)
    sys.path.insert(0, os.path.join(SOURCE, "Scripts"))
    import user_guide_tables
    return user_guide_tables.load(SOURCE)


def property_names(proxies, key):
    proxy = proxies.get(key)
    if proxy is None:
        check(False, "base proxy %s/%s not found in Plugin/**/*.xml" % key)
        return []
    names = []
    base = (proxy.get("base_proxygroup"), proxy.get("base_proxyname"))
    # A representation derives from ParaView's Surface representation, which ParaView
    # documents; the guide names the properties the plugin adds.
    if base[1] and base[0] != "representations":
        names = property_names(proxies, base)
    for child in proxy:
        if child.tag.endswith("Property") and child.get("name") and child.get("name") not in names:
            names.append(child.get("name"))
    return names


def sections(markdown):
    """[(heading line, level, section text)] of every Markdown heading outside code."""
    lines = markdown.split("\n")
    heads = []
    fenced = False
    for i, line in enumerate(lines):
        if line.startswith("```"):
            fenced = not fenced
        elif not fenced:
            m = re.match(r"(#+)\s", line)
            if m:
                heads.append((i, len(m.group(1))))
    out = []
    for n, (i, level) in enumerate(heads):
        end = len(lines)
        for j, other in heads[n + 1:]:
            if other <= level:
                end = j
                break
        out.append((lines[i], level, "\n".join(lines[i:end])))
    return out


def check_user_guide():
    with open(GUIDE, encoding="utf-8") as f:
        guide = sections(f.read())
    proxies = load_proxies()
    checked = 0
    for key, proxy in proxies.items():
        if key[0].startswith("internal"):
            continue
        name = key[1]
        label = proxy.get("label") or name
        found = [s for s in guide if "`%s`" % name in s[0] and label in s[0]]
        check(found, "user-guide.md: no heading with the label '%s' and `%s` (proxy %s/%s)"
              % (label, name, key[0], name))
        if not found:
            continue
        text = found[0][2]
        for prop in property_names(proxies, key):
            checked += 1
            check("`%s`" % prop in text, "user-guide.md, section '%s': property `%s` of %s "
                  "is not named" % (found[0][0].lstrip("# "), prop, name))
    print("user guide: %d proxies, %d properties checked" %
          (sum(1 for k in proxies if not k[0].startswith("internal")), checked))


# --- 2. The runnable pvpython blocks ----------------------------------------------------

def blocks(path, fence):
    """[(line number, code)] of the blocks whose opening fence is exactly `fence`."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    out = []
    i = 0
    while i < len(lines):
        if lines[i].strip() == fence:
            start = i + 1
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                i += 1
            out.append((start + 1, "\n".join(lines[start:i])))
        i += 1
    return out


def run_python_blocks():
    from paraview import simple
    from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow

    scratch = tempfile.mkdtemp(prefix="PiDocumentation")
    os.symlink(os.path.join(SOURCE, "Testing"), os.path.join(scratch, "Testing"))
    here = os.getcwd()
    original = vtkOutputWindow.GetInstance()
    ran = 0
    try:
        os.chdir(scratch)
        for path in RUNNABLE:
            check(os.path.exists(path), "missing %s" % path)
            if not os.path.exists(path):
                continue
            found = blocks(path, "```python run")
            check(found or path not in REQUIRED,
                  "%s has no ```python run block" % os.path.relpath(path, SOURCE))
            if not found:
                continue
            simple.ResetSession()
            namespace = {"__name__": "__doc_example__"}
            for line, code in found:
                where = "%s:%d" % (os.path.relpath(path, SOURCE), line)
                window = vtkStringOutputWindow()
                vtkOutputWindow.SetInstance(window)
                try:
                    exec(compile(code, where, "exec"), namespace)
                    error = None
                except Exception:
                    error = traceback.format_exc(limit=3)
                finally:
                    vtkOutputWindow.SetInstance(original)
                text = window.GetOutput()
                if isinstance(text, bytes):
                    text = text.decode("utf-8", "replace")
                ran += 1
                check(error is None, "%s: the block raised\n%s" % (where, error))
                check("ERROR" not in text, "%s: VTK reported an error:\n%s" % (where, text[:1500]))
            # A block may build a pipeline without executing it: update everything the
            # page made, so an error in a filter's settings shows too.
            window = vtkStringOutputWindow()
            vtkOutputWindow.SetInstance(window)
            try:
                for proxy in simple.GetSources().values():
                    proxy.UpdatePipeline()
            finally:
                vtkOutputWindow.SetInstance(original)
            text = window.GetOutput()
            if isinstance(text, bytes):
                text = text.decode("utf-8", "replace")
            check("ERROR" not in text, "%s: VTK reported an error updating its pipelines:\n%s"
                  % (os.path.relpath(path, SOURCE), text[:1500]))
    finally:
        os.chdir(here)
        shutil.rmtree(scratch, ignore_errors=True)
    print("python blocks: %d run" % ran)


# --- 3. The C++ blocks compile ---------------------------------------------------------

def compile_cpp_blocks(compiler, include_dirs):
    found = blocks(README, "```cpp")
    for line, code in found:
        with tempfile.NamedTemporaryFile("w", suffix=".cxx", delete=False) as f:
            f.write(code)
        command = [compiler, "-std=c++17", "-fsyntax-only", f.name]
        command += ["-I" + d for d in include_dirs if d]
        result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                universal_newlines=True)
        os.unlink(f.name)
        check(result.returncode == 0, "README.md:%d: the C++ block does not compile:\n%s"
              % (line, result.stdout[-3000:]))
    print("C++ blocks: %d compiled" % len(found))


check_user_guide()
run_python_blocks()
if len(sys.argv) > 3:
    compile_cpp_blocks(sys.argv[2], sys.argv[3].split("|"))
finish()
