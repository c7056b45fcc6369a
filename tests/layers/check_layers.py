#!/usr/bin/env python3
"""check_layers.py — the kernel's includes must follow the data flow.

The kernel (kernel/cdyn/) is one folder per stage, read bottom-up in the order the data
flows: scene → mesh → spaces → matrices A, B, C, L → mass model and constraints (M, G, α)
→ scheme → step QP → outputs.  A file may include only its own stage and the stages
ALLOWED lists for it (the same table is in docs/kernel_map.md).  The QP solvers, for
instance, see only S, r and the bounds: qp/ may not include schemes/, problems/ or mesh/.

The umbrella header cdyn/cdyn.hpp must include every header of the stages.

Usage: check_layers.py KERNEL_DIR    (exit 1 and one line per offending include)
"""
import pathlib
import re
import sys

# stage -> the stages it may include (besides itself)
ALLOWED = {
    "base": set(),
    "mesh": {"base"},
    "fe": {"base", "mesh"},
    "linalg": {"base"},
    "mass": {"base", "mesh", "fe", "linalg"},
    "problems": {"base", "mesh", "fe", "linalg", "mass"},
    "exact": {"base"},
    "wellposedness": {"base", "mesh", "fe", "linalg", "mass", "problems"},
    "qp": {"base", "linalg"},
    "schemes": {"base", "mesh", "fe", "linalg", "mass", "problems", "qp"},
    "post": {"base", "mesh", "fe", "linalg", "mass", "problems", "qp", "schemes"},
}
UMBRELLA = "cdyn.hpp"  # includes every stage
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]cdyn/([^">]+)[">]')


def stage_of(relative: str) -> str:
    """The stage folder of a path relative to kernel/cdyn/, e.g. 'qp/pdas/pdas.hpp' -> 'qp'."""
    return relative.split("/", 1)[0] if "/" in relative else ""


def main() -> int:
    root = pathlib.Path(sys.argv[1]) / "cdyn"
    errors = []
    files = sorted(p for p in root.rglob("*") if p.suffix in (".hpp", ".cpp"))
    for path in files:
        rel = path.relative_to(root).as_posix()
        if rel == UMBRELLA:
            continue
        stage = stage_of(rel)
        if stage not in ALLOWED:
            errors.append(f"{rel}: not in a stage folder (known: {', '.join(ALLOWED)})")
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            target = m.group(1)
            if target == "version.hpp":  # generated, stage-free
                continue
            to = stage_of(target)
            if to == stage or to in ALLOWED[stage]:
                continue
            why = "a flat include path (use the stage folder)" if not to else f"{stage}/ may not include {to}/"
            errors.append(f"{rel}:{number}: #include <cdyn/{target}>: {why}")
    umbrella = root / UMBRELLA
    if umbrella.exists():
        included = {m.group(1) for line in umbrella.read_text(encoding="utf-8").splitlines() if (m := INCLUDE.match(line))}
        for path in files:
            rel = path.relative_to(root).as_posix()
            if path.suffix == ".hpp" and rel != UMBRELLA and rel not in included:
                errors.append(f"{UMBRELLA}: does not include <cdyn/{rel}>")
    for e in errors:
        print(e)
    print(f"check_layers: {len(files)} files, {len(errors)} include(s) against the data flow")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
