"""The ParaView XML and the format's documentation against the primitive catalogue.

    python3 TestPiPrimitiveCatalogue.py SOURCE_DIR PICATALOGUEXML

The catalogue (Filters/Core/PiPrimitiveCatalogue.h, read here through
vtkPiPrimitive.GetCatalogueJSON()) is the single source of truth of the primitive
types. What cannot iterate it, because ParaView reads it as static text, is checked:

1. The Pi Primitive proxy (in any XML file under Plugin/, Plugin/**/*.xml, as ParaView
   gets it: a file with catalogue markers is first filled in by the build tool
   PICATALOGUEXML, Plugin/XML/PiCatalogueXML.cxx, as the plugin's build does): its `Type`
   enumeration holds exactly the catalogue's types, value = index, text = label, in
   order; every parameter of the catalogue is a property of the proxy with enough
   elements and the catalogue's default; a parameter shown only for some types
   (a GenericDecorator on `Type`) is shown for exactly the types that have it, and one
   without such a decorator is in the Placement group (whose widget shows it per type),
   as are the properties that every type's 3D widget edits.
2. Documentation/pisurf-format.md: its primitive table lists the catalogue's types in
   order (`key` / Label) with their parameter keys.
3. Documentation/user-guide.md: Pi Primitive's `Type` row lists the catalogue's labels.
"""
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

from pitesting import check, finish

from pisurfaces import vtkPiPrimitive

SOURCE = os.path.abspath(sys.argv[1])
GENERATOR = sys.argv[2]
CATALOGUE = json.loads(vtkPiPrimitive.GetCatalogueJSON())

check(len(CATALOGUE) == vtkPiPrimitive.GetNumberOfTypes(), "GetNumberOfTypes disagrees")
check([t["type"] for t in CATALOGUE] == list(range(len(CATALOGUE))),
      "catalogue entries out of order")


def types_with(prop):
    """The type values whose parameters include property `prop`."""
    return {t["type"] for t in CATALOGUE if any(p["property"] == prop for p in t["parameters"])}


# --- 1. The Pi Primitive proxy ---------------------------------------------------------

def primitive_proxies():
    files = sorted(glob.glob(os.path.join(SOURCE, "Plugin", "**", "*.xml"), recursive=True))
    check(files, "no XML file under %s/Plugin" % SOURCE)
    found = []
    for path in files:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        if "@PrimitiveTypes@" in text or "@TypesWith:" in text:
            with tempfile.TemporaryDirectory() as tmp:
                filled = os.path.join(tmp, os.path.basename(path))
                run = subprocess.run([GENERATOR, path, filled], capture_output=True, text=True)
                check(run.returncode == 0, "%s %s: %s" % (GENERATOR, path, run.stderr.strip()))
                if run.returncode != 0:
                    continue
                root = ET.parse(filled).getroot()
        else:
            root = ET.fromstring(text)
        for group in root.iter("ProxyGroup"):
            for proxy in group:
                if proxy.get("name") == "PiPrimitive" and len(proxy):
                    found.append((os.path.relpath(path, SOURCE), proxy))
    return found


def numbers(text):
    return [float(v) for v in (text or "").split()]


def check_proxy(where, proxy):
    props = {child.get("name"): child for child in proxy if child.get("name")}

    # The Type enumeration: value = index, text = label.
    prop = props.get("Type")
    check(prop is not None, "%s: Pi Primitive has no Type property" % where)
    if prop is None:
        return
    entries = [(int(e.get("value")), e.get("text")) for e in prop.iter("Entry")]
    expected = [(t["type"], t["label"]) for t in CATALOGUE]
    check(entries == expected, "%s: Type enumeration %s, the catalogue has %s"
          % (where, entries, expected))
    check(numbers(prop.get("default_values")) == [0],
          "%s: Type's default is not the first type" % where)

    # Each parameter's property: its elements and default.
    seen = set()
    for t in CATALOGUE:
        for p in t["parameters"]:
            name = p["property"]
            what = "%s: %s.%s (property %s)" % (where, t["key"], p["key"], name)
            prop = props.get(name)
            check(prop is not None, what + " is not a property of Pi Primitive")
            if prop is None or name in seen:
                continue
            seen.add(name)
            count = int(prop.get("number_of_elements", "1"))
            check(count >= p["count"], what + ": %d elements, the catalogue has %d"
                  % (count, p["count"]))
            if p["kind"] == "text":
                # vtkPiPrimitive's Expression starts empty, as the XML's; the catalogue's
                # default is what the editor starts a new primitive with.
                check(prop.tag == "StringVectorProperty", what + " is not a string")
                continue
            tag = "IntVectorProperty" if p["kind"] == "integer" else "DoubleVectorProperty"
            check(prop.tag == tag, what + " is a %s, not a %s" % (prop.tag, tag))
            default = numbers(prop.get("default_values"))
            check(default[:p["count"]] == p["default"],
                  what + ": XML default %s, the catalogue's %s" % (default, p["default"]))

    # Visibility: a decorator on Type shows a parameter for exactly its types; without
    # one, the Placement group shows it.
    groups = [g for g in proxy.iter("PropertyGroup")
              if g.get("panel_widget") == "pi_primitive_placement"]
    check(len(groups) == 1, "%s: no single Placement group (pi_primitive_placement)" % where)
    placed = {p.get("name") for g in groups for p in g.iter("Property")}
    for name in sorted(seen):
        shown = set()
        decorated = False
        for d in props[name].iter("PropertyWidgetDecorator"):
            if d.get("type") == "GenericDecorator" and d.get("property") == "Type":
                decorated = True
                shown |= {int(v) for v in (d.get("value") or d.get("values", "")).split()}
        if decorated:
            check(shown == types_with(name), "%s: %s is shown for types %s, the catalogue "
                  "gives it to %s" % (where, name, sorted(shown), sorted(types_with(name))))
        else:
            check(name in placed, "%s: %s has no Type decorator and is not in the "
                  "Placement group: every type would show it" % (where, name))

    # The 3D widget of each type edits properties of the Placement group.
    for t in CATALOGUE:
        for key in ("widget_size", "widget_direction"):
            if t[key]:
                check(t[key] in placed, "%s: %s's widget edits %s, not in the Placement "
                      "group" % (where, t["key"], t[key]))


proxies = primitive_proxies()
check(len(proxies) == 1, "Pi Primitive defined %d times in Plugin/**/*.xml" % len(proxies))
for where, proxy in proxies:
    check_proxy(where, proxy)


# --- 2. Documentation/pisurf-format.md ---------------------------------------------------

FORMAT = os.path.join(SOURCE, "Documentation", "pisurf-format.md")
rows = []
with open(FORMAT, encoding="utf-8") as f:
    in_table = False
    for line in f:
        if line.startswith("| type (`.pisurf` / VTK)"):
            in_table = True
            continue
        if in_table:
            if not line.startswith("|"):
                break
            if line.startswith("|---"):
                continue
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            m = re.match(r"`([^`]+)` / (\w+)$", cells[0])
            check(m, "pisurf-format.md: cannot read the type cell %r" % cells[0])
            if m:
                rows.append((m.group(1), m.group(2), re.findall(r"`([^`]+)`", cells[1])))
check(rows, "pisurf-format.md: no primitive table (| type (`.pisurf` / VTK) | ...)")
expected = [(t["key"], t["label"], [p["key"] for p in t["parameters"]]) for t in CATALOGUE]
check(rows == expected, "pisurf-format.md's primitive table:\n  %s\nthe catalogue:\n  %s"
      % (rows, expected))

# --- 3. The user guide's Type row of Pi Primitive -----------------------------------------

GUIDE = os.path.join(SOURCE, "Documentation", "user-guide.md")
with open(GUIDE, encoding="utf-8") as f:
    type_rows = [line for line in f
                 if line.startswith("| `Type` |") and "The kind of primitive" in line]
check(len(type_rows) == 1, "user-guide.md: %d rows for Pi Primitive's `Type`" % len(type_rows))
for line in type_rows:
    values = re.findall(r"`([^`]+)`", line.split("Values:", 1)[-1])
    check(values == [t["label"] for t in CATALOGUE],
          "user-guide.md: Pi Primitive's Type values %s, the catalogue's %s"
          % (values, [t["label"] for t in CATALOGUE]))

finish()
