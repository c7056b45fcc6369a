"""Scenes for the commands: a file, the embedded default, or a dict with a scene's keys.

A dict is written as the TOML text of a scene file (docs/scenes.md): its top-level
tables become ``[table]`` sections and deeper tables inline tables, so that
``{"mesh": {"kind": "unit_square", "n": 10}, "output": {"probes": {"c": [0.5, 0.5]}}}``
reads as a file with the same keys would; the command line's code then checks it
(an unknown key is an error naming it).  Overrides (``set``) are ``--set key=value``
strings, or a dict {key: value}: a str value is taken as typed after ``--set key=``
(``"40"`` is a number, ``"backward_euler"`` a string, as on the command line), any
other Python value is written as its TOML value.
"""

import json
import numbers
import os


def toml_value(value, key="value"):
    """The TOML text of a Python value (str, bool, number, list, dict)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return float.__repr__(float(value))  # the shortest text that reads back as the same double
    if isinstance(value, (str, os.PathLike)):
        return json.dumps(os.fspath(value), ensure_ascii=False)  # JSON's escapes are TOML's
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{toml_key(k)} = {toml_value(v, k)}" for k, v in value.items()) + " }"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v, key) for v in value) + "]"
    if hasattr(value, "tolist"):  # a numpy array or scalar
        return toml_value(value.tolist(), key)
    raise TypeError(f"{key}: cannot write a {type(value).__name__} in a scene")


def command_line_value(value, key):
    """The text after `--set key=`: a str as it is, anything else as TOML."""
    return value if isinstance(value, str) else toml_value(value, key)


def toml_key(key):
    key = str(key)
    bare = key and all(c.isascii() and (c.isalnum() or c in "_-") for c in key)
    return key if bare else json.dumps(key, ensure_ascii=False)


def toml_text(scene):
    """A scene dict as the text of a scene file."""
    top = [f"{toml_key(k)} = {toml_value(v, k)}" for k, v in scene.items() if not isinstance(v, dict)]
    tables = [f"\n[{toml_key(k)}]\n" + "".join(f"{toml_key(kk)} = {toml_value(vv, f'{k}.{kk}')}\n" for kk, vv in v.items())
              for k, v in scene.items() if isinstance(v, dict)]
    return "\n".join(top) + "\n" + "".join(tables)


def source(scene):
    """(path, text) for the command line's code: a file path, or TOML text named 'dict'."""
    if scene is None:
        return "", ""
    if isinstance(scene, dict):
        return "dict", toml_text(scene)
    if isinstance(scene, (str, os.PathLike)):
        return os.fspath(scene), ""
    raise TypeError(f"scene: expected None, a path or a dict, got {type(scene).__name__}")


def overrides(set):
    """--set strings from a dict {key: value} or a list of 'key=value' strings."""
    if set is None:
        return []
    if isinstance(set, dict):
        return [f"{k}={command_line_value(v, k)}" for k, v in set.items()]
    if isinstance(set, str):
        return [set]
    return [str(a) for a in set]
