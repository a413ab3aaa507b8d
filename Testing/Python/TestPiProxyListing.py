"""Every public proxy of the plugin, as ParaView builds it, against a recorded listing.

    pvpython TestPiProxyListing.py <listing> [--record]

The listing (Testing/Data/proxy_listing.txt, recorded from the one-file XML before it
was split by feature) names, for each proxy of the plugin outside the `internal_*`
groups, sorted by group and name: the proxy's attributes (label, class), its
documentation, then its hints, output ports and property groups, then every property in the order of the
Properties panel (inherited ones included, as ParaView flattens base proxies): its XML
element in full (attributes, domains, hints, help text, whitespace normalised) and the
values ParaView gives it on a new proxy, with each domain's class and content (range
bounds, enumeration entries). Restructuring the XML must not change one line; a change
of the public interface records the listing again with --record and says so.
"""
import difflib
import ctypes
import os
import sys
import tempfile
import xml.etree.ElementTree as ET

from paraview import servermanager
from paraview import simple  # noqa: F401  (connects, loads the plugin)

from pitesting import check, finish


def text(value):
    return " ".join((value or "").split())


LIBC = ctypes.CDLL(None)


def parsed(element):
    """A vtkPVXMLElement as an ElementTree element (vtkPVXMLElement does not list its
    attributes to Python: its PrintXML() writes to the C++ standard output, whose
    buffer C's fflush empties; ParaView 5.13 leaves it unflushed)."""
    sys.stdout.flush()
    saved = os.dup(1)
    with tempfile.TemporaryFile() as out:
        os.dup2(out.fileno(), 1)
        try:
            element.PrintXML()
            LIBC.fflush(None)
        finally:
            os.dup2(saved, 1)
            os.close(saved)
        out.seek(0)
        return ET.fromstring(out.read())


def element_lines(element, indent):
    """An XML element as lines: tag, sorted attributes, normalised text, children."""
    line = indent + "<%s%s>" % (element.tag, "".join(' %s="%s"' % kv
                                                    for kv in sorted(element.attrib.items())))
    data = text(element.text)
    if data:
        line += " " + data
    lines = [line]
    for child in element:
        lines += element_lines(child, indent + "  ")
    return lines


def domain_lines(prop, indent):
    lines = []
    iterator = prop.NewDomainIterator()
    iterator.Begin()
    while not iterator.IsAtEnd():
        domain = iterator.GetDomain()
        line = indent + "domain %s %s" % (iterator.GetKey(), domain.GetClassName())
        if domain.IsA("vtkSMEnumerationDomain"):
            line += " " + repr([(domain.GetEntryText(i), domain.GetEntryValue(i))
                                for i in range(domain.GetNumberOfEntries())])
        elif domain.IsA("vtkSMStringListDomain"):
            line += " " + repr([domain.GetString(i) for i in range(domain.GetNumberOfStrings())])
        elif domain.IsA("vtkSMDoubleRangeDomain") or domain.IsA("vtkSMIntRangeDomain"):
            bounds = []
            for i in range(max(1, prop.GetNumberOfElements())):
                bounds.append((domain.GetMinimum(i) if domain.GetMinimumExists(i) else None,
                               domain.GetMaximum(i) if domain.GetMaximumExists(i) else None))
            line += " " + repr(bounds)
        lines.append(line)
        iterator.Next()
    return lines


def value_line(prop, indent):
    if prop.IsA("vtkSMVectorProperty"):
        values = [prop.GetElement(i) for i in range(prop.GetNumberOfElements())]
        return indent + "value %s %r" % (prop.GetClassName(), values)
    if prop.IsA("vtkSMProxyProperty"):
        return indent + "value %s %d proxies" % (prop.GetClassName(), prop.GetNumberOfProxies())
    return indent + "value %s" % prop.GetClassName()


def plugin_class(name):
    """The plugin's VTK classes are named vtkPi... (not ParaView's vtkPiecewiseFunction)."""
    return bool(name) and name.startswith("vtkPi") and not name.startswith("vtkPiecewise")


def listing():
    pxm = servermanager.vtkSMProxyManager.GetProxyManager().GetActiveSessionProxyManager()
    definitions = pxm.GetProxyDefinitionManager()
    keys = set()
    iterator = definitions.NewIterator()
    iterator.GoToFirstItem()
    while not iterator.IsDoneWithTraversal():
        keys.add((iterator.GetGroupName(), iterator.GetProxyName()))
        iterator.GoToNextItem()
    lines = []
    for group, name in sorted(keys):
        if group.startswith("internal_"):
            continue
        # A representation derives from ParaView's Surface representation: only what
        # the plugin's XML adds is listed, so the listing does not change with ParaView.
        if group == "representations":
            definition = definitions.GetProxyDefinition(group, name)
        else:
            definition = definitions.GetCollapsedProxyDefinition(group, name, None, False)
        if definition is None:
            continue
        definition = parsed(definition)
        if definition.get("class") is None and definition.get("group"):
            # A listing of a proxy of another group (Clip's "Clip Type" list, ...).
            target = definitions.GetCollapsedProxyDefinition(
                definition.get("group"), definition.get("name"), None, False)
            if target is not None and plugin_class(parsed(target).get("class")):
                lines.append("listing %s/%s -> %s/%s" % (group, name, definition.get("group"),
                                                         definition.get("name")))
            continue
        if not plugin_class(definition.get("class")):
            continue
        attributes = sorted(definition.attrib.items())
        lines.append("proxy %s/%s%s" % (group, name, "".join(' %s="%s"' % kv for kv in attributes)))
        proxy = pxm.NewProxy(group, name)
        check(proxy is not None, "cannot create %s/%s" % (group, name))
        properties = []
        # The proxy's documentation first: where ParaView's flattening puts it depends
        # only on which XML element of the inheritance chain holds it.
        for child in definition.findall("Documentation"):
            lines += element_lines(child, "  ")
        for child in definition:
            if child.tag.endswith("Property") and child.get("name"):
                properties.append(child)
            elif child.tag != "Documentation":  # hints, output ports, groups: in order
                lines += element_lines(child, "  ")
        for child in properties:
            prop_name = child.get("name")
            lines.append("  property %s" % prop_name)
            lines += element_lines(child, "    ")
            prop = proxy.GetProperty(prop_name) if proxy else None
            check(prop is not None, "%s/%s has no property %s" % (group, name, prop_name))
            if prop is not None:
                lines.append(value_line(prop, "    "))
                lines += domain_lines(prop, "    ")
        if proxy is not None and group != "representations":
            # Every property the proxy has is one of the definition's.
            own = {p.get("name") for p in properties}
            iterator = proxy.NewPropertyIterator()
            iterator.Begin()
            while not iterator.IsAtEnd():
                check(iterator.GetKey() in own, "%s/%s: property %s not in its definition"
                      % (group, name, iterator.GetKey()))
                iterator.Next()
    return lines


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    lines = listing()
    check(any(line.startswith("proxy sources/PiSurface ") for line in lines),
          "the plugin is not loaded (no sources/PiSurface)")
    if "--record" in argv[2:]:
        with open(argv[1], "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
        print("recorded %d lines in %s" % (len(lines), argv[1]))
    else:
        with open(argv[1], encoding="utf-8") as f:
            reference = f.read().splitlines()
        diff = list(difflib.unified_diff(reference, lines, "recorded", "now", lineterm=""))
        for line in diff[:200]:
            print(line)
        check(not diff, "the proxies differ from %s (%d diff lines)" % (argv[1], len(diff)))
        print("%d lines, %d proxies compared" % (len(lines),
                                                sum(l.startswith("proxy ") for l in lines)))
    finish()


if __name__ == "__main__":
    main(sys.argv)
