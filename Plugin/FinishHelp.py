# SPDX-License-Identifier: BSD-3-Clause
"""Turns ParaView's generated proxy help into the pages a user should see.

ParaView writes one HTML page per proxy of the server-manager XML, as the XML
states it: internal base proxies get their own pages, a proxy's page lists only
the properties written inside it (not those it inherits through
base_proxygroup/base_proxyname), properties with panel_visibility="never" are
listed, and a proxy registered again in another group by reference gets a copy
of its page. This script, run between the page generation and the Qt help
compilation, gives each user-visible proxy one page with every property the
Properties panel can show, in the panel's order (inherited ones first), and
removes the pages of internal proxies and of references.

The XML comes as several files (Plugin/XML/, one per family of proxies) in the order
the plugin loads them: a proxy's base (base_proxygroup/base_proxyname) must be in an
earlier file or earlier in the same file, otherwise the build stops here with the
names of both.

Usage: FinishHelp.py <help directory> <stamp file> <server-manager XML>...
"""

import os
import re
import sys
import xml.etree.ElementTree as ET

ROW = re.compile(r"[ \t]*<tr>\s*<th>([^<]+)</th>.*?</tr>\n?", re.S)
TABLE_END = re.compile(r"[ \t]*</table>")
PROXY_NAME = re.compile(r'<meta name="proxy_name" contents="([^"]+)"/>')
FINISHED = '<meta name="finished_by" contents="FinishHelp.py"/>'


class Proxy:
    def __init__(self, group, element):
        self.group = group
        self.name = element.get("name")
        self.base = None
        if element.get("base_proxygroup") and element.get("base_proxyname"):
            self.base = (element.get("base_proxygroup"), element.get("base_proxyname"))
        self.hidden = set()
        self.shown = set()
        for child in element:
            if not child.tag.endswith("Property") or not child.get("name"):
                continue
            if child.get("panel_visibility") == "never":
                self.hidden.add(child.get("name"))
            else:
                self.shown.add(child.get("name"))

    @property
    def key(self):
        return "%s.%s" % (self.group, self.name)


def read_proxies(xml_files):
    proxies = {}
    for path in xml_files:
        for group in ET.parse(path).getroot().iter("ProxyGroup"):
            if group.get("name") == "representations":
                continue  # displays: ParaView gives them no help page of their own
            for element in group:
                if not element.tag.endswith("Proxy") or not element.get("name"):
                    continue
                if element.get("group") and not element.get("class"):
                    continue  # a reference to a proxy of another group
                proxy = Proxy(group.get("name"), element)
                if proxy.base and proxy.base not in proxies:
                    sys.exit("FinishHelp: %s (%s) derives from %s.%s, which no earlier XML "
                             "file defines: list the base's file first"
                             % (proxy.key, os.path.basename(path), proxy.base[0], proxy.base[1]))
                proxies[(proxy.group, proxy.name)] = proxy
    return proxies


def find_pages(directory):
    """The generated page of each proxy, by its "group.name" (the file names escape
    characters of the group, so they are found by the page's proxy_name).

    Pages as ParaView generated them are kept in the subfolder "generated", which the
    help compilation does not read, so that running this script again (after it
    changed, without the pages being generated again) starts from the same input."""
    pristine = os.path.join(directory, "generated")
    os.makedirs(pristine, exist_ok=True)
    for entry in os.listdir(directory):
        path = os.path.join(directory, entry)
        if entry.endswith(".html"):
            with open(path, encoding="utf-8") as f:
                text = f.read()
            if PROXY_NAME.search(text) and FINISHED not in text:
                with open(os.path.join(pristine, entry), "w", encoding="utf-8") as f:
                    f.write(text)
    pages = {}
    for entry in os.listdir(pristine):
        with open(os.path.join(pristine, entry), encoding="utf-8") as f:
            match = PROXY_NAME.search(f.read())
        if match:
            pages[match.group(1)] = entry
    return pages


def page_rows(directory, pages, proxy):
    """The property rows of a generated page, in order, as (name, html)."""
    if proxy.key not in pages:
        sys.exit("FinishHelp: no generated help page for %s" % proxy.key)
    with open(os.path.join(directory, "generated", pages[proxy.key]), encoding="utf-8") as f:
        return [(m.group(1), m.group(0)) for m in ROW.finditer(f.read())]


def effective_rows(directory, pages, proxies, proxy, cache):
    """Rows of a proxy with those of its bases, a redefinition replacing the base's."""
    key = (proxy.group, proxy.name)
    if key in cache:
        return cache[key]
    own = page_rows(directory, pages, proxy)
    rows = []
    if proxy.base:
        base = proxies.get(proxy.base)
        if base is None:
            sys.exit("FinishHelp: %s names the unknown base proxy %s.%s"
                     % (proxy.key, proxy.base[0], proxy.base[1]))
        own_names = {name for name, _ in own}
        rows = [r for r in effective_rows(directory, pages, proxies, base, cache)
                if r[0] not in own_names]
    rows += own
    cache[key] = rows
    return rows


def hidden_names(proxies, proxy):
    """Properties never shown in the panel: hidden where last defined."""
    chain = []
    while proxy is not None:
        chain.append(proxy)
        proxy = proxies.get(proxy.base) if proxy.base else None
    hidden = set()
    for p in reversed(chain):  # base first; a redefinition decides
        hidden -= p.shown
        hidden |= p.hidden
    return hidden


def main(argv):
    if len(argv) < 4:
        sys.exit(__doc__)
    directory, stamp, xml_files = argv[1], argv[2], argv[3:]
    proxies = read_proxies(xml_files)
    pages = find_pages(directory)
    cache = {}
    finished = {}
    for proxy in proxies.values():
        if proxy.group.startswith("internal_"):
            continue
        hidden = hidden_names(proxies, proxy)
        finished[proxy.key] = [html for name, html
                               in effective_rows(directory, pages, proxies, proxy, cache)
                               if name not in hidden]
    for key, rows in finished.items():
        with open(os.path.join(directory, "generated", pages[key]), encoding="utf-8") as f:
            text = f.read()
        first = ROW.search(text)
        end = TABLE_END.search(text)
        if end is None:
            sys.exit("FinishHelp: the page of %s has no property table" % key)
        start = first.start() if first else end.start()
        text = text[:start] + "".join(rows) + text[end.start():]
        text = PROXY_NAME.sub(lambda m: m.group(0) + "\n        " + FINISHED, text, count=1)
        with open(os.path.join(directory, pages[key]), "w", encoding="utf-8") as f:
            f.write(text)
    for key, entry in pages.items():
        if key not in finished and os.path.exists(os.path.join(directory, entry)):
            os.remove(os.path.join(directory, entry))
    with open(stamp, "w", encoding="utf-8") as f:
        f.write("\n".join(sorted(finished)) + "\n")


if __name__ == "__main__":
    main(sys.argv)
