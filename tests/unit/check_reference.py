#!/usr/bin/env python3
"""docs/reference.md's table of the panel's pins against the panel.

Every pin hal/fixed_atc_probe_panel.py creates must be in the table of
"## HAL pins" with its type and direction; no row may name a pin that is not
created. The names are read from the panel as written: its newpin calls
through its module constants and for loops. A source this script cannot
follow fails it with the place, so it never passes by reading less. (The
component's pins and config.json's keys are declared once in the code and
their references generated: references_are_current.)

usage: check_reference.py PROJECT_ROOT    (exit 0: complete, 1: not, with one
line per problem naming what is missing and where)
"""
import ast
import re
import sys
from pathlib import Path

PROBLEMS = []


def problem(text):
    PROBLEMS.append(text)


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def panel_pins(root):
    source = (root / "hal/fixed_atc_probe_panel.py").read_text()
    tree = ast.parse(source)
    constants = {}

    def sequence(node, env):
        """A tuple or list of names (A + B + C of them too), not a loop's string."""
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            return sequence(node.left, env) and sequence(node.right, env)
        return isinstance(node, (ast.Tuple, ast.List)) or \
            (isinstance(node, ast.Name) and node.id not in env)

    def value(node, env):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return [node.value]
        if isinstance(node, (ast.Tuple, ast.List)):
            out = []
            for element in node.elts:
                out += value(element, env)
            return out
        if isinstance(node, ast.Name):
            if node.id in env:
                return env[node.id]
            if node.id in constants:
                return constants[node.id]
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            left, right = value(node.left, env), value(node.right, env)
            if sequence(node.left, env) and sequence(node.right, env):
                return left + right
            return [a + b for a in left for b in right]
        raise LookupError("hal/fixed_atc_probe_panel.py:%d: cannot follow %s (teach %s)" %
                          (node.lineno, ast.dump(node)[:60], Path(__file__).name))

    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and \
                isinstance(node.targets[0], ast.Name):
            try:
                constants[node.targets[0].id] = value(node.value, {})
            except LookupError:
                pass
    pins = {}
    kinds = {"HAL_BIT": "bit", "HAL_S32": "s32", "HAL_U32": "u32", "HAL_FLOAT": "float"}

    def makes_pins(node):
        return any(isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute) and
                   n.func.attr == "newpin" for n in ast.walk(node))

    def visit(node, env):
        if not makes_pins(node):
            return
        if isinstance(node, ast.For) and isinstance(node.target, ast.Name):
            for item in value(node.iter, env):
                for child in node.body:
                    visit(child, dict(env, **{node.target.id: [item]}))
            return
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
                node.func.attr == "newpin":
            kind, direction = (a.attr if isinstance(a, ast.Attribute) else "?"
                               for a in node.args[1:3])
            for name in value(node.args[0], env):
                pins[name] = (kinds.get(kind, kind), direction.replace("HAL_", "").lower())
            return
        for child in ast.iter_child_nodes(node):
            visit(child, env)

    try:
        visit(tree, {})
    except LookupError as e:
        problem(str(e))
    if not pins:
        problem("hal/fixed_atc_probe_panel.py: no newpin calls found")
    return pins


# ---------------------------------------------------------------- reference reading

REFERENCE = "docs/reference.md"


def section(reference, title):
    start = reference.find("\n## " + title + "\n")
    if start < 0:
        problem('%s: no section "## %s"' % (REFERENCE, title))
        return ""
    end = reference.find("\n## ", start + 1)
    return reference[start:end if end >= 0 else len(reference)]


def tables(text):
    """Each table as a list of rows, each a list of cells (header and rule dropped)."""
    found, rows = [], None
    for line in text.splitlines():
        if line.startswith("|"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if rows is None:
                rows = []
                continue  # the header
            if all(re.match(r"^:?-+:?$", c) for c in cells):
                continue
            rows.append(cells)
        elif rows is not None:
            found.append(rows)
            rows = None
    if rows is not None:
        found.append(rows)
    return found


def first_cell_names(rows):
    for cells in rows:
        for name in re.findall(r"`([^`]+)`", cells[0]):
            yield name, cells


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: check_reference.py PROJECT_ROOT")
    root = Path(sys.argv[1])
    reference = (root / REFERENCE).read_text()

    # pins
    pin_tables = tables(section(reference, "HAL pins"))
    for index, (who, source, pins) in enumerate(
            [("panel fatc-panel", "hal/fixed_atc_probe_panel.py", panel_pins(root))]):
        if len(pin_tables) <= index:
            problem('%s: "## HAL pins" has no table %d (the %s\'s pins)' % (REFERENCE, index + 1, who))
            continue
        shown = {}
        for name, cells in first_cell_names(pin_tables[index]):
            shown[name] = (cells[1] if len(cells) > 1 else "", cells[2] if len(cells) > 2 else "")
        for name, (kind, direction) in sorted(pins.items()):
            if name not in shown:
                problem('%s: pin %s of the %s (%s, %s %s) is missing from table %d of '
                        '"## HAL pins"' % (REFERENCE, name, who, source, kind, direction, index + 1))
            elif shown[name] != (kind, direction):
                problem('%s: pin %s of the %s is %s %s in %s, the table says %s %s' %
                        (REFERENCE, name, who, kind, direction, source, *shown[name]))
        for name in sorted(set(shown) - set(pins)):
            problem('%s: pin %s in table %d of "## HAL pins" is not created by %s' %
                    (REFERENCE, name, index + 1, source))

    for line in PROBLEMS:
        print(line)
    if PROBLEMS:
        return 1
    print("%s: %d panel pins, all in the reference table" %
          (REFERENCE, len(panel_pins(root))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
