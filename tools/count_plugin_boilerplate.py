#!/usr/bin/env python3
"""Counts how plugins name their parameters and ports, and finds names written outside the
config/port structs' `visit`.

Usage: tools/count_plugin_boilerplate.py [PLUGINS_DIR] [--check]

Prints, for the C++ sources under PLUGINS_DIR (default: plugins/ next to this tool):
  declarations   `s.add_<type>("name")` parameter declarations and `s.input<T>(...)` /
                 `s.output<T>(...)` port declarations in spec() functions
  string reads   `ctx.param<T>("name")`, `ctx.input<T>("name")`, `ctx.output<T>("name")`,
                 `ctx.is_wired("name")`, `param_error("name", ...)`, `output_path_param("name")`
  visit fields   `v.field("name", ...)` and `v.port("name", ...)` in visit functions
  spec lines     lines of spec() functions and of Config/Ports visit functions
With --check: exit status 1 (and the offending lines) when any string read or string
declaration is left, i.e. a parameter or port name is written anywhere but in a visit.
"""
import pathlib
import re
import sys

PATTERNS = {
    "param declarations (add_*)": r"\badd_(?:bool|int|double|string|list|string_list)\(\s*\"",
    "port declarations (s.input/s.output)": r"\b(?!ctx\b|context\b)\w+\.(?:input|output)<[^>]*>\(\s*\"",
    "param reads (ctx.param<T>(\"...\"))": r"\bparam<[^>]*>\(\s*\"",
    "port reads (input/output<T>(\"...\"))": r"\b(?:ctx|context)\.(?:input|output)<[^>]*>\(\s*\"",
    "is_wired(\"...\")": r"\bis_wired\(\s*\"",
    "param_error(\"...\")": r"\bparam_error\(\s*\"",
    "output_path_param(\"...\")": r"\boutput_path_param\(\s*\"",
}
VISIT = {
    "visit fields (v.field)": r"\bv\.field\(",
    "visit ports (v.port)": r"\bv\.port\(",
}


def function_lines(text, header_regex):
    total = 0
    for m in re.finditer(header_regex, text):
        depth, i = 0, text.index("{", m.start())
        start = i
        while True:
            if text[i] == "{":
                depth += 1
            elif text[i] == "}":
                depth -= 1
                if depth == 0:
                    break
            i += 1
        total += text[start:i].count("\n") + 1
    return total


def main():
    args = [a for a in sys.argv[1:] if a != "--check"]
    root = pathlib.Path(args[0]) if args else pathlib.Path(__file__).resolve().parent.parent / "plugins"
    files = sorted(p for p in root.rglob("*") if p.suffix in (".cpp", ".hpp"))
    counts = {k: 0 for k in list(PATTERNS) + list(VISIT)}
    offenders = []
    spec_lines = visit_lines = 0
    for f in files:
        text = f.read_text()
        for name, rx in PATTERNS.items():
            for m in re.finditer(rx, text):
                counts[name] += 1
                line = text.count("\n", 0, m.start()) + 1
                offenders.append(f"{f}:{line}: {text.splitlines()[line - 1].strip()}")
        for name, rx in VISIT.items():
            counts[name] += len(re.findall(rx, text))
        spec_lines += function_lines(text, r"PluginSpec\s+\w+::spec\(\)\s*\{")
        visit_lines += function_lines(text, r"void\s+[\w:]+::visit\(V& v\)\s*\{")
    print(f"{len(files)} files under {root}")
    for name, n in counts.items():
        print(f"  {name:45s} {n}")
    print(f"  {'spec() lines':45s} {spec_lines}")
    print(f"  {'visit() lines':45s} {visit_lines}")
    if "--check" in sys.argv and offenders:
        print("\nnames written outside a visit:")
        for o in offenders:
            print("  " + o)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
