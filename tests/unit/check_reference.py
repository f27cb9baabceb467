#!/usr/bin/env python3
"""docs/reference.md's reference tables against the sources they describe.

Every config.json key that src/core/config/config.cpp accepts must have a row in
the table of "## config.json reference" (a key with keys below it, such as
`loading`, counts as there when one of its own keys is), and every row there
must name a key the reader accepts. Every pin hal/fixed_atc_probe_panel.py
creates must be in the table of "## HAL pins" with its type and direction;
no row may name a pin that is not created. (The component's own pins are
generated from src/linuxcnc/pin_list.hpp into docs/pins.md:
references_are_current.)

The names are read from the sources as written: config.cpp's
reject_unknown_keys lists (the keys it does not refuse), their paths
followed through join_path, local variables and call sites; the panel's
newpin calls through its module constants and for loops. A source this
script cannot follow fails it with the place, so it never passes by reading
less.

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


# ---------------------------------------------------------------- C++ reading

DEFINITION = re.compile(
    r"^( {0,2})(?!(?:if|for|while|switch|return|else|case|do|throw)\b)"
    r"[A-Za-z_][\w:<>,*& ]*?[\s*&>](\w+)\(([^;{}]*?)\)\s*(?:const\s*)?\{",
    re.MULTILINE)
STRING = re.compile(r'^"((?:[^"\\]|\\.)*)"$')


def split_arguments(text):
    """Top-level comma-separated arguments of a call's argument text."""
    parts, depth, current, quoted = [], 0, "", False
    for i, c in enumerate(text):
        if quoted:
            current += c
            if c == '"' and text[i - 1] != "\\":
                quoted = False
            continue
        if c == '"':
            quoted = True
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(current.strip())
            current = ""
            continue
        current += c
    if current.strip():
        parts.append(current.strip())
    return parts


def closing(text, start, opener, closer):
    """Where the `closer` matching the `opener` at `start` is, skipping string
    literals; None when it never comes."""
    depth, quoted = 0, False
    for i in range(start, len(text)):
        c = text[i]
        if quoted:
            if c == '"' and text[i - 1] != "\\":
                quoted = False
            continue
        if c == '"':
            quoted = True
        elif c == opener:
            depth += 1
        elif c == closer:
            depth -= 1
            if depth == 0:
                return i
    return None


def call_arguments(text, open_paren):
    """The argument text of the call whose '(' is at open_paren, and its end."""
    end = closing(text, open_paren, "(", ")")
    if end is None:
        raise ValueError("unbalanced parentheses")
    return text[open_paren + 1:end], end


class CppFile:
    def __init__(self, path, *more):
        """`more`: files read as one with `path` (the reader the config's calls go through)."""
        self.path = path
        self.text = "\n".join(p.read_text() for p in (*more, path))
        # Function definitions: name, parameter names, body start and end.
        self.functions = []
        for m in DEFINITION.finditer(self.text):
            params = []
            for p in split_arguments(m.group(3)):
                p = p.split("=")[0].strip()
                names = re.findall(r"(\w+)\s*$", p)
                params.append(names[0] if names else "")
            start = m.end() - 1
            end = self.matching_brace(start)
            self.functions.append({"name": m.group(2), "params": params, "start": start,
                                   "end": end})

    def matching_brace(self, start):
        end = closing(self.text, start, "{", "}")
        return len(self.text) if end is None else end

    def function_at(self, offset):
        """The innermost definition holding offset."""
        holding = [f for f in self.functions if f["start"] <= offset <= f["end"]]
        return min(holding, key=lambda f: f["end"] - f["start"]) if holding else None

    def where(self, offset):
        return "%s:%d" % (self.path.name, line_of(self.text, offset))

    def resolve(self, expr, offset, depth=0):
        """Every text `expr` can be at offset: literals, join_path, item.key()
        (a pocket number: N), locals and parameters (through call sites)."""
        expr = expr.strip()
        if depth > 10:
            raise LookupError("%s: %s: followed too deep" % (self.where(offset), expr))
        literal = STRING.match(expr)
        if literal:
            return {literal.group(1)}
        if expr.endswith(".key()"):
            return {"N"}
        join = re.match(r"^join_path\((.*)\)$", expr, re.DOTALL)
        if join:
            a, b = split_arguments(join.group(1))
            return {x + "." + y if x else y
                    for x in self.resolve(a, offset, depth + 1)
                    for y in self.resolve(b, offset, depth + 1)}
        if re.match(r"^\w+$", expr):
            function = self.function_at(offset)
            if function is None:
                raise LookupError("%s: %s: not inside a function" % (self.where(offset), expr))
            body = self.text[function["start"]:offset]
            assigned = list(re.finditer(r"\b%s\s*=\s*([^;]+);" % expr, body))
            if assigned:
                return self.resolve(assigned[-1].group(1),
                                    function["start"] + assigned[-1].start(), depth + 1)
            if expr in function["params"]:
                index = function["params"].index(expr)
                values = set()
                for call in re.finditer(r"(?<![\w:])%s\(" % function["name"], self.text):
                    if self.function_at(call.start()) is None:
                        continue  # a definition or declaration, not a call
                    arguments, _ = call_arguments(self.text, call.end() - 1)
                    arguments = split_arguments(arguments)
                    if len(arguments) <= index:
                        continue
                    values |= self.resolve(arguments[index], call.start(), depth + 1)
                if not values:
                    raise LookupError("%s: parameter %s of %s: no call site found" %
                                      (self.where(offset), expr, function["name"]))
                return values
        raise LookupError("%s: cannot follow %r" % (self.where(offset), expr))


def accepted_config_keys(root):
    cpp = CppFile(root / "src/core/config/config.cpp", root / "src/core/config/reader.hpp")
    keys = set()
    calls = list(re.finditer(r"reject_unknown_keys\(", cpp.text))
    for call in calls:
        if cpp.function_at(call.start()) is None:
            continue
        arguments, _ = call_arguments(cpp.text, call.end() - 1)
        arguments = split_arguments(arguments)
        if len(arguments) != 3 or not arguments[2].startswith("{"):
            problem("%s: reject_unknown_keys without a {list} of keys: teach %s to read it" %
                    (cpp.where(call.start()), Path(__file__).name))
            continue
        listed = re.findall(r'"(\w+)"', arguments[2])
        try:
            parents = cpp.resolve(arguments[1], call.start())
        except LookupError as e:
            problem("%s (teach %s to follow it)" % (e, Path(__file__).name))
            continue
        for parent in parents:
            for key in listed:
                keys.add(parent + "." + key if parent else key)
    if not keys:
        problem("src/core/config/config.cpp: no reject_unknown_keys lists found")
    return keys


def panel_pins(root):
    source = (root / "hal/fixed_atc_probe_panel.py").read_text()
    tree = ast.parse(source)
    constants = {}

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
            if isinstance(node.left, (ast.Tuple, ast.List, ast.Name)) and \
                    isinstance(node.right, (ast.Tuple, ast.List, ast.Name)) and \
                    not (isinstance(node.left, ast.Name) and node.left.id in env):
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

    # config.json keys
    keys = accepted_config_keys(root)
    config_tables = tables(section(reference, "config.json reference"))
    rows = {name for name, _ in first_cell_names(config_tables[0])} if config_tables else set()
    if not config_tables:
        problem('%s: "## config.json reference" has no table' % REFERENCE)
    for key in sorted(keys):
        children = [k for k in rows if k.startswith(key + ".")]
        if key not in rows and not children:
            problem("%s: config key %s (accepted by src/core/config/config.cpp) is missing from "
                    'the table of "## config.json reference"' % (REFERENCE, key))
    for row in sorted(rows):
        if row not in keys and not any(k.startswith(row + ".") for k in keys):
            problem("%s: config key %s in the table of \"## config.json reference\" is "
                    "not accepted by src/core/config/config.cpp" % (REFERENCE, row))

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
    print("%s: %d config keys and %d pins, all in the reference tables" %
          (REFERENCE, len(keys), len(panel_pins(root))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
