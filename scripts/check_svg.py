#!/usr/bin/env python3
"""Checks that FILE is valid SVG, as far as a drawing of ours needs: well-formed
XML with an <svg> root; and that each TEXT given is the text of one of its
<text> elements, or starts one.   check_svg.py FILE [TEXT...]"""
import sys
import xml.etree.ElementTree as ET

SVG = "{http://www.w3.org/2000/svg}"


def main():
    try:
        root = ET.parse(sys.argv[1]).getroot()
    except (OSError, ET.ParseError) as e:
        sys.exit("%s: not valid XML: %s" % (sys.argv[1], e))
    if root.tag != SVG + "svg":
        sys.exit("%s: the root is %s, not svg" % (sys.argv[1], root.tag))
    texts = [t.text or "" for t in root.iter(SVG + "text")]
    for wanted in sys.argv[2:]:
        if not any(t.startswith(wanted) for t in texts):
            sys.exit("%s: no text says %r" % (sys.argv[1], wanted))
    print("%s: valid SVG, %d elements%s" % (sys.argv[1], sum(1 for _ in root.iter()),
                                            ", every text asked for" if sys.argv[2:] else ""))


if __name__ == "__main__":
    main()
