"""ParaView's help for the plugin, as compiled into it (the .qch), against the proxies
pvpython loads: one page per proxy a user can create, no page of an internal base
proxy or a duplicate, and each page lists exactly the properties the Properties panel
can show (inherited ones included, panel_visibility="never" ones left out)."""
import os
import re
import sqlite3
import sys
import zlib

from pitesting import check, finish

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

qch = sys.argv[1]
check(os.path.exists(qch), "the compiled help exists: " + qch)
database = sqlite3.connect(qch)
pages = {}
for name, data in database.execute(
        "SELECT FileNameTable.Name, FileDataTable.Data FROM FileNameTable "
        "JOIN FileDataTable ON FileNameTable.FileId = FileDataTable.Id"):
    if name.endswith(".html"):
        pages[name] = zlib.decompress(bytes(data)[4:]).decode("utf-8")  # qCompress
titles = [t for (t,) in database.execute("SELECT Title FROM FileNameTable")]

proxy_pages = {}
for name, text in pages.items():
    match = re.search(r'<meta name="proxy_name" contents="([^"]+)"', text)
    if match:
        proxy_pages[match.group(1)] = text

expected = {"sources.PiSurface", "sources.PiSurfaceModelReader", "sources.PiPrimitive",
            "sources.PiMoleculeReader", "filters.PiProduct", "filters.PiRayCast",
            "filters.ImageBasedTriangulation", "filters.PiSampleFunction",
            "filters.MolecularPiSurface", "implicit_functions.PiSurfaceFunction",
            "writers.PiSurfaceModelWriter"}
check(set(proxy_pages) == expected,
      "one page per user-visible proxy, got %s" % sorted(proxy_pages))
check(not any(k.startswith("internal_") for k in proxy_pages), "no internal proxy page")
check(not any(t.startswith("Pi") and " " not in t and t != "PiSurfaces" for t in titles if t),
      "every page title is a label, not a proxy's XML name: %s" % titles)
check(titles.count("Pi Surface Function") == 1, "the implicit function has one page")

manager = servermanager.ProxyManager()
for key, text in sorted(proxy_pages.items()):
    group, name = key.split(".")
    proxy = manager.SMProxyManager.NewProxy(group, name)
    check(proxy is not None, "pvpython creates %s" % key)
    if proxy is None:
        continue
    shown = []
    iterator = proxy.NewPropertyIterator()
    iterator.Begin()
    while not iterator.IsAtEnd():
        prop = iterator.GetProperty()
        if (not prop.GetInformationOnly() and not prop.GetIsInternal()
                and prop.GetPanelVisibility() != "never"):
            shown.append(iterator.GetKey())
        iterator.Next()
    documented = re.findall(r"<tr>\s*<th>([^<]+)</th>", text)
    check(sorted(documented) == sorted(shown),
          "%s documents exactly its panel's properties:\n  missing %s\n  extra %s"
          % (key, sorted(set(shown) - set(documented)), sorted(set(documented) - set(shown))))
    check(len(documented) == len(set(documented)), "%s lists each property once" % key)

surface = proxy_pages["sources.PiSurface"]
for prop in ("Resolution", "Method", "Blending", "Model"):
    check("<th>%s</th>" % prop in surface, "Pi Surface's page documents %s" % prop)
check("KeepLastValidOutput" not in surface, "Pi Surface's page hides KeepLastValidOutput")
check("WidgetReferenceBounds" not in proxy_pages["sources.PiPrimitive"],
      "Pi Primitive's page hides WidgetReferenceBounds")
finish()
