#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Print the property table of each proxy in Plugin/**/*.xml as Markdown, from the XML's
own defaults and <Documentation>, for Documentation/user-guide.md.

    python3 Scripts/user_guide_tables.py [ProxyName ...]

Inherited properties (base_proxygroup/base_proxyname) are listed with the proxy that
inherits them. Python.TestPiDocumentation checks that the guide names every proxy and
property; this script gives a new proxy's table to paste and edit.
"""
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def load(root=ROOT):
    """(group, name) -> element for every proxy definition of every XML file under Plugin/."""
    proxies = {}
    for path in sorted(glob.glob(os.path.join(root, "Plugin", "**", "*.xml"), recursive=True)):
        for group in ET.parse(path).getroot().iter("ProxyGroup"):
            for proxy in group:
                # <Proxy group=... name=.../> with no body only lists a proxy in another group.
                if proxy.get("name") is None or (proxy.get("group") and len(proxy) == 0):
                    continue
                if not proxy.tag.endswith("Proxy"):
                    continue  # <Extension> of a ParaView proxy: no proxy of its own
                proxies[(group.get("name"), proxy.get("name"))] = proxy
    return proxies


def properties(proxies, key):
    """The properties of a proxy, its base proxies' first, in the order the panel shows."""
    proxy = proxies[key]
    out = []
    base = (proxy.get("base_proxygroup"), proxy.get("base_proxyname"))
    # A base outside the plugin's XML is ParaView's (the Surface representation).
    if base[1] and base in proxies:
        out = properties(proxies, base)
    for child in proxy:
        if child.tag.endswith("Property") and child.get("name"):
            out = [p for p in out if p.get("name") != child.get("name")] + [child]
    return out


def user_visible(key):
    return not key[0].startswith("internal")


def clean(text):
    return re.sub(r"\s+", " ", (text or "").strip())


def entries(enum):
    """(value, text) of an enumeration. The Pi Primitive's Type enumeration is empty in the
    source (PiCatalogueXML fills it in from the primitive catalogue at build time): its
    entries come from the built pisurfaces module when it is importable."""
    found = [(e.get("value"), e.get("text")) for e in enum.iter("Entry")]
    if found:
        return found
    try:
        import json
        from pisurfaces import vtkPiPrimitive
    except ImportError:
        return [("0", "(the primitive catalogue's labels: set PYTHONPATH to build/lib/python)")]
    return [(str(t["type"]), t["label"]) for t in json.loads(vtkPiPrimitive.GetCatalogueJSON())]


def default_of(prop):
    default = prop.get("default_values")
    if default is None or default == "":
        return "—"
    enum = prop.find("EnumerationDomain")
    if enum is not None:
        names = dict(entries(enum))
        return " ".join(names.get(v, v) for v in default.split())
    if prop.find("BooleanDomain") is not None:
        return {"0": "off", "1": "on"}.get(default, default)
    if prop.get("element_types") and prop.find("ArrayListDomain") is not None:
        return default.split()[-1]  # an input-array selection: the array's name
    return default


def table(proxies, key):
    rows = ["| property | default | meaning |", "|---|---|---|"]
    for prop in properties(proxies, key):
        doc = prop.find("Documentation")
        text = clean(doc.text if doc is not None else "").replace("|", "\\|")
        enum = prop.find("EnumerationDomain")
        if enum is not None:
            text += " Values: " + ", ".join("`%s`" % t for _, t in entries(enum)) + "."
        visibility = prop.get("panel_visibility")
        if visibility == "advanced":
            text += " *(advanced)*"
        elif visibility == "never":
            text += " *(hidden)*"
        rows.append("| `%s` | %s | %s |" % (prop.get("name"), default_of(prop), text))
    return "\n".join(rows)


if __name__ == "__main__":
    proxies = load()
    for key in proxies:
        if user_visible(key) and (len(sys.argv) < 2 or key[1] in sys.argv[1:]):
            print("### %s (`%s`)\n\n%s\n" % (proxies[key].get("label") or key[1], key[1],
                                              table(proxies, key)))
