"""Plugin/Reference.md from Plugin/MLSDeform.xml: the proxies' and properties' documentation is
written once, in the XML's <Documentation> elements (which ParaView's help and the Properties
panel's tooltips show); this script turns it into the markdown reference page.

    python3 Plugin/make_reference.py [--check] [--xml PATH] [--output PATH]

Paths default to MLSDeform.xml and Reference.md beside this script. With --check nothing is
written: the exit status is 1, with a message, when the page on disk differs from what the XML
gives (the test Plugin.ReferenceUpToDate), 0 when it is up to date. Python 3 standard library
only; the output depends on the XML alone (its order), not on the paths or the machine."""
import argparse
import os
import re
import string
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_XML = os.path.join(HERE, 'MLSDeform.xml')
DEFAULT_OUTPUT = os.path.join(HERE, 'Reference.md')

# The proxy groups documented, and what a proxy of each is called on the page.
KINDS = {'sources': 'source', 'filters': 'filter', 'writers': 'writer'}
VALUE_TYPES = {'IntVectorProperty': 'integer', 'DoubleVectorProperty': 'number',
               'IdTypeVectorProperty': 'integer', 'StringVectorProperty': 'string'}
ELEMENT_TYPES = {'0': 'integer', '1': 'number', '2': 'string'}


def pretty_label(name):
    """ParaView 5.11's label for a property without one (vtkSMProperty::CreateNewPrettyLabel): a
    space before every capital letter not preceded by a capital letter or a space."""
    label = name[:1]
    previous_capital = False
    for c in name[1:]:
        if 'A' <= c <= 'Z':
            if not previous_capital and label[-1] != ' ':
                label += ' '
            previous_capital = True
        else:
            previous_capital = False
        label += c
    return label


def python_name(label):
    """The name paraview.simple gives a proxy or a property (paraview.make_name_valid)."""
    valid = '_' + string.ascii_letters + string.digits
    name = ''.join(c for c in label if c in valid)
    if name and not name[0].isalpha():
        name = 'a' + name
    return name


def collapse(text):
    return ' '.join((text or '').split())


def md(text):
    """Plain documentation text as markdown that shows it as written (also inside a table cell):
    the characters markdown would read as emphasis, code, table cells, links, HTML or entities
    are escaped."""
    text = text.replace('\\', '\\\\')
    text = re.sub(r'&(?=#?\w+;)', '&amp;', text)
    text = re.sub(r'<(?=[A-Za-z/!?])', '&lt;', text)
    text = re.sub(r'(?<!\w)_|_(?!\w)', r'\\_', text)
    for c in '*`|~':
        text = text.replace(c, '\\' + c)
    return text.replace('](', '\\](')


def code(text):
    return '`%s`' % text


def numbers(values):
    """'0 0 0' -> '(0, 0, 0)', '1' -> '1'."""
    values = values.split()
    return values[0] if len(values) == 1 else '(%s)' % ', '.join(values)


def is_proxy(element):
    return element.tag.endswith('Proxy') and element.get('name') is not None


def is_property(element):
    return element.tag.endswith('Property') and element.get('name') is not None


def proxy_documentation(proxy):
    """(short help, long help, description) of a proxy or property, whitespace collapsed."""
    doc = proxy.find('Documentation')
    if doc is None:
        return '', '', ''
    return collapse(doc.get('short_help')), collapse(doc.get('long_help')), collapse(''.join(doc.itertext()))


def definitions(root):
    """{(group, name): element} of every proxy, and the proxies in XML order as (group, element)."""
    found, order = {}, []
    for group in root.iter('ProxyGroup'):
        for proxy in group:
            if is_proxy(proxy):
                found[(group.get('name'), proxy.get('name'))] = proxy
                order.append((group.get('name'), proxy))
    return found, order


def properties(proxy, found):
    """The proxy's properties, a base proxy's first (base_proxygroup, base_proxyname) with the
    proxy's own of the same name in their place, then the proxy's others: as ParaView merges them."""
    merged = []
    base = found.get((proxy.get('base_proxygroup'), proxy.get('base_proxyname')))
    if base is not None:
        merged = properties(base, found)
    own = [p for p in proxy if is_property(p)]
    names = {p.get('name'): p for p in own}
    merged = [names.pop(p.get('name'), p) for p in merged]
    return merged + [p for p in own if p.get('name') in names]


def domains(prop):
    return {d.tag: d for d in prop if d.tag.endswith('Domain')}


def hint(element, tag):
    hints = element.find('Hints')
    return hints.find(tag) if hints is not None else None


def input_array_domain(proxy, found, name):
    """The InputArrayDomain called name among the proxy's (and its base's) input properties."""
    for prop in properties(proxy, found):
        for domain in prop.iter('InputArrayDomain'):
            if domain.get('name') == name:
                return domain
    return None


def array_description(proxy, found, domain):
    what = 'an input array'
    source = input_array_domain(proxy, found, domain.get('input_domain_name'))
    if source is not None:
        attribute = source.get('attribute_type', 'any')
        what = 'an input %s array' % ('point or cell' if attribute == 'any' else attribute)
        if source.get('number_of_components'):
            what += ' of %s component%s' % (source.get('number_of_components'),
                                             '' if source.get('number_of_components') == '1' else 's')
    if domain.get('none_string'):
        what += ', or %s' % domain.get('none_string')
    return what


def property_type(prop):
    tag = prop.tag
    found = domains(prop)
    if tag == 'InputProperty':
        kind = 'input'
        if prop.get('multiple_input') == '1':
            kind += ', repeatable'
        if hint(prop, 'Optional') is not None:
            kind += ', optional'
        return kind
    if tag == 'ProxyProperty':
        groups = {p.get('group') for p in prop.iter('Proxy')}
        return 'implicit function' if groups == {'implicit_functions'} else 'proxy'
    if 'BooleanDomain' in found:
        return 'boolean'
    if 'EnumerationDomain' in found:
        return 'enumeration'
    if 'ArrayListDomain' in found:
        return 'array name' if prop.get('repeat_command') != '1' else 'list of names'
    if 'FileListDomain' in found:
        return 'file name'
    if 'DataAssemblyDomain' in found:
        return 'list of names'
    base = VALUE_TYPES.get(tag, tag)
    per_command = int(prop.get('number_of_elements_per_command') or 0)
    if prop.get('repeat_command') == '1':
        if per_command > 1:
            kinds = [ELEMENT_TYPES.get(t, base) for t in (prop.get('element_types') or '').split()]
            if kinds:
                return 'table, rows of %d (%s)' % (per_command, ', '.join(kinds))
            return 'table, rows of %d %ss' % (per_command, base)
        return 'list of %ss' % base
    count = int(prop.get('number_of_elements') or 1)
    return '%d %ss' % (count, base) if count > 1 else base


def property_default(prop):
    found = domains(prop)
    if prop.tag == 'InputProperty':
        return '–'
    if prop.tag == 'ProxyProperty':
        proxies = prop.find('ProxyListDomain')
        first = proxies.find('Proxy') if proxies is not None else None
        return first.get('name') if first is not None else '–'
    values = prop.get('default_values')
    if values is None or values == 'none':
        return '–'
    if 'BooleanDomain' in found:
        return {'1': 'on', '0': 'off'}.get(values, values)
    if 'EnumerationDomain' in found:
        texts = {e.get('value'): e.get('text') for e in found['EnumerationDomain'].iter('Entry')}
        return texts.get(values, values)
    if prop.tag == 'StringVectorProperty':
        return values if values != '' else '(empty)'
    return numbers(values)


def range_text(domain):
    """'0 – 10', '≥ 0', '≤ 1' of a range domain; one number for components that are all alike."""
    def bound(values):
        values = (values or '').split()
        return values[0] if len(set(values)) == 1 else numbers(' '.join(values)) if values else ''
    low, high = bound(domain.get('min')), bound(domain.get('max'))
    if low and high:
        return '%s – %s' % (low, high)
    if low:
        return '≥ %s' % low
    if high:
        return '≤ %s' % high
    return ''


def property_values(proxy, found, prop):
    parts = []
    for tag, domain in domains(prop).items():
        if tag in ('IntRangeDomain', 'DoubleRangeDomain'):
            parts.append(range_text(domain))
        elif tag == 'EnumerationDomain':
            parts.append(', '.join('%s (%s)' % (code(e.get('text')), e.get('value')) for e in domain.iter('Entry')))
        elif tag == 'BooleanDomain':
            parts.append('on (1), off (0)')
        elif tag == 'ProxyListDomain':
            parts.append(', '.join(code(p.get('name')) for p in domain.iter('Proxy')))
        elif tag == 'ArrayListDomain':
            parts.append(array_description(proxy, found, domain))
        elif tag == 'DataTypeDomain':
            parts.append(', '.join(code(t.get('value')) for t in domain.iter('DataType')))
        elif tag == 'ProducerDomain':
            parts.append('from ' + ', '.join(code(p.get('name')) for p in domain.iter('Proxy')))
        elif tag == 'DataAssemblyDomain':
            parts.append("the input's blocks, or names")
    return '; '.join(p for p in parts if p) or '–'


def internal(prop):
    return prop.get('panel_visibility') == 'never' or prop.get('information_only') == '1'


def label_of(element):
    return element.get('label') or pretty_label(element.get('name'))


def name_cell(prop):
    label = label_of(prop)
    py = python_name(label)
    cell = '**%s**<br>%s' % (md(label), code(py))
    if py != prop.get('name'):
        cell += ' (XML %s)' % code(prop.get('name'))
    if prop.get('panel_visibility') == 'advanced':
        cell += '<br>advanced'
    return cell


def proxy_facts(group, proxy, found):
    """The line under a proxy's heading: kind, class, group, names, menu, files, ports, base."""
    kind = KINDS[group]
    reader = hint(proxy, 'ReaderFactory')
    writer = hint(proxy, 'WriterFactory')
    if reader is not None:
        kind = 'reader'
    facts = [kind, 'class ' + code(proxy.get('class')), 'group ' + code(group), 'XML name ' + code(proxy.get('name'))]
    py = python_name(label_of(proxy))
    facts.append('Python ' + code(('servermanager.writers.%s' if group == 'writers' else '%s()') % py))
    menu = hint(proxy, 'ShowInMenu')
    if menu is not None:
        facts.append('menu *Filters > %s*' % md(menu.get('category') or 'Alphabetical'))
    for factory, action in ((reader, '*File > Open*'), (writer, '*File > Save Data*')):
        if factory is not None:
            extensions = ', '.join(code('.' + e) for e in factory.get('extensions', '').split())
            facts.append('%s: %s files, listed as "%s"' % (action, extensions, md(factory.get('file_description', ''))))
    ports = [p for p in proxy.iter('OutputPort')]
    if ports:
        facts.append('outputs ' + ', '.join('%s %s' % (p.get('index'), code(p.get('name'))) for p in ports))
    base = found.get((proxy.get('base_proxygroup'), proxy.get('base_proxyname')))
    if base is not None:
        facts.append('shares the properties of %s (%s)' % (code(base.get('name')), code(base.get('class'))))
    return ' · '.join(facts)


def anchor(text):
    """GitHub's anchor of a heading."""
    text = re.sub(r'[^\w\- ]', '', text.lower())
    return text.replace(' ', '-')


def heading(proxy):
    return '%s (%s)' % (label_of(proxy), code(proxy.get('name')))


def generate(xml_text):
    root = ET.fromstring(xml_text)
    found, order = definitions(root)
    documented = [(group, proxy) for group, proxy in order if group in KINDS]
    others = [(group, proxy) for group, proxy in order if group not in KINDS]
    out = ['# MLSDeform plugin reference', '',
           '<!-- Generated by Plugin/make_reference.py from Plugin/MLSDeform.xml: do not edit. Edit the',
           "     XML's <Documentation> elements and run python3 Plugin/make_reference.py (the test",
           '     Plugin.ReferenceUpToDate fails while this page is stale). -->', '',
           "The plugin's readers, filters and writers with their properties, as Plugin/MLSDeform.xml declares",
           "and documents them: ParaView shows the same text in its help (the *?* button of the Properties",
           "panel) and in each property's tooltip. A property's Python name is the one `paraview.simple` uses",
           "(`MLSDeform(Input=..., StretchWeight=0)`); *advanced* properties show after the Properties panel's",
           'gear button. Ranges are those of the panel\'s widgets.', '']
    for group, proxy in documented:
        title = heading(proxy)
        out.append('- [%s](#%s)' % (title, anchor(title)))
    out.append('')
    for group, proxy in documented:
        out += ['## ' + heading(proxy), '', proxy_facts(group, proxy, found), '']
        short, long, description = proxy_documentation(proxy)
        if short:
            out += ['*%s*' % md(short), '']
        if long and long != description:
            out += [md(long), '']
        if description:
            out += [md(description), '']
        props = properties(proxy, found)
        shown = [p for p in props if not internal(p)]
        hidden = [p for p in props if internal(p)]
        if shown:
            out += ['| property | type | default | range / values | documentation |', '|---|---|---|---|---|']
            for prop in shown:
                out.append('| %s | %s | %s | %s | %s |' % (
                    name_cell(prop), property_type(prop), md(property_default(prop)),
                    property_values(proxy, found, prop), md(proxy_documentation(prop)[2]) or '–'))
            out.append('')
        if hidden:
            out.append('Internal, set by ParaView or the GUI and not shown in the Properties panel:')
            for prop in hidden:
                doc = proxy_documentation(prop)[2]
                out.append('- %s (%s)%s' % (code(prop.get('name')), property_type(prop), ': ' + md(doc) if doc else ''))
            out.append('')
    if others:
        out += ['## Other proxies', '',
                'Declared by the plugin for its own use, not in any menu: ' +
                ', '.join('%s/%s (%s)' % (code(group), code(proxy.get('name')), code(proxy.get('class')))
                          for group, proxy in others) + '.', '']
    return '\n'.join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--check', action='store_true', help='write nothing; exit 1 when the page is stale')
    parser.add_argument('--xml', default=DEFAULT_XML, help='the plugin XML (default: MLSDeform.xml beside this script)')
    parser.add_argument('--output', default=DEFAULT_OUTPUT, help='the page (default: Reference.md beside this script)')
    args = parser.parse_args()
    with open(args.xml, encoding='utf-8') as f:
        page = generate(f.read())
    shown = 'Plugin/Reference.md' if os.path.abspath(args.output) == DEFAULT_OUTPUT else args.output
    if args.check:
        try:
            with open(args.output, encoding='utf-8', newline='') as f:
                current = f.read()
        except FileNotFoundError:
            current = None
        if current != page:
            print('%s is stale: run python3 Plugin/make_reference.py' % shown, file=sys.stderr)
            return 1
        print('%s is up to date' % shown)
        return 0
    with open(args.output, 'w', encoding='utf-8', newline='\n') as f:
        f.write(page)
    return 0


if __name__ == '__main__':
    sys.exit(main())
