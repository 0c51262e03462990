"""Run configuration: JSON file + `--set key.path=value` overrides, checked
against config/schema.json, the single statement of the rules and defaults
that the C++ executable (cpp/config.cpp) applies too, with the same wording."""

import copy
import json
import math
from pathlib import Path

SCHEMA_PATH = Path(__file__).resolve().parents[2] / "config" / "schema.json"
EXIT_CONFIG_ERROR = 2


class ConfigError(Exception):
    """A problem with the user's input: the message names file, key and value."""


def _fmt(value):
    return json.dumps(value, separators=(",", ":"))


def _edit_distance(a, b):
    """Optimal string alignment distance: insertions, deletions,
    substitutions and swaps of neighbours each count 1."""
    d = [[i + j if i * j == 0 else 0 for j in range(len(b) + 1)] for i in range(len(a) + 1)]
    for i in range(1, len(a) + 1):
        for j in range(1, len(b) + 1):
            d[i][j] = min(d[i - 1][j] + 1, d[i][j - 1] + 1,
                          d[i - 1][j - 1] + (a[i - 1] != b[j - 1]))
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                d[i][j] = min(d[i][j], d[i - 2][j - 2] + 1)
    return d[len(a)][len(b)]


def closest_key(key, candidates):
    """The candidate nearest to a misspelt key (at most a third of it edited)."""
    best = min(candidates, key=lambda c: (_edit_distance(key, c), c), default=None)
    if best is not None and _edit_distance(key, best) <= max(1, len(key) // 3):
        return best
    return None


def _parse_override(text, source):
    if "=" not in text:
        raise ConfigError(f"{source}: --set '{text}': expected key.path=value")
    key, raw = text.split("=", 1)
    try:
        value = json.loads(raw)
    except json.JSONDecodeError:
        value = raw  # a bare word such as mumps is a string
    return key.strip(), value


def apply_override(cfg, key, value, source):
    """Set cfg[a][b]... = value for key 'a.b...' (list items by index)."""
    parts = key.split(".")
    node = cfg
    for depth, part in enumerate(parts[:-1]):
        where = ".".join(parts[:depth + 1])
        if isinstance(node, list) and part.isdigit() and int(part) < len(node):
            node = node[int(part)]
        elif isinstance(node, dict):
            node = node.setdefault(part, {})
        else:
            raise ConfigError(f"{source}: --set {key}: '{where}' is not an object")
    last = parts[-1]
    if isinstance(node, list) and last.isdigit() and int(last) < len(node):
        node[int(last)] = value
    elif isinstance(node, dict):
        node[last] = value
    else:
        raise ConfigError(f"{source}: --set {key}: cannot set '{last}' here")


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _check_bounds(v, rule, path, source):
    if "min" in rule and v < rule["min"]:
        raise ConfigError(f"{source}: {path} = {_fmt(v)}: must be >= {_fmt(rule['min'])}")
    if "exclusive_min" in rule and v <= rule["exclusive_min"]:
        raise ConfigError(f"{source}: {path} = {_fmt(v)}: must be > {_fmt(rule['exclusive_min'])}")


def _check(value, rule, path, source):
    """Validate `value` against `rule`; return it with defaults filled in."""
    t = rule["type"]
    alternative = rule.get("alternative")  # a word allowed instead of the value
    if alternative is not None and value == alternative:
        return value

    def wrong(expected):
        if alternative is not None:
            expected += f" or {_fmt(alternative)}"
        return ConfigError(f"{source}: {path} = {_fmt(value)}: expected {expected}")

    if t == "object":
        if not isinstance(value, dict):
            raise wrong("an object")
        keys = rule["keys"]
        for k in value:
            if k not in keys:
                near = closest_key(k, list(keys))
                hint = f" (did you mean '{_join(path, near)}'?)" if near else ""
                raise ConfigError(f"{source}: {_join(path, k)}: unknown key{hint}")
        out = {}
        for k, sub in keys.items():
            if k in value:
                out[k] = _check(value[k], sub, _join(path, k), source)
            elif "default" in sub:
                out[k] = _check(copy.deepcopy(sub["default"]), sub, _join(path, k), source)
            elif sub.get("required"):
                raise ConfigError(f"{source}: {_join(path, k)}: missing required key")
        return out
    if t == "map":
        if not isinstance(value, dict):
            raise wrong("an object")
        return {k: _check(v, rule["values"], _join(path, k), source) for k, v in value.items()}
    if t == "number":
        if not _is_number(value):
            raise wrong("a number")
        _check_bounds(value, rule, path, source)
        return float(value)
    if t == "integer":
        if not (isinstance(value, int) and not isinstance(value, bool)):
            raise wrong("an integer")
        _check_bounds(value, rule, path, source)
        return value
    if t == "boolean":
        if not isinstance(value, bool):
            raise wrong("true or false")
        return value
    if t == "string":
        if not isinstance(value, str):
            raise wrong("a string")
        if "enum" in rule and value not in rule["enum"]:
            raise wrong("one of " + ", ".join(rule["enum"]))
        return value
    if t == "scalar":
        if not (isinstance(value, (str, bool)) or _is_number(value)):
            raise wrong("a string, number or boolean")
        return value
    if t == "vector":
        n = rule["length"]
        if not (isinstance(value, list) and len(value) == n and all(map(_is_number, value))):
            raise wrong(f"a list of {n} numbers")
        return [float(v) for v in value]
    if t == "matrix":
        r, c = rule["shape"]
        if not (isinstance(value, list) and len(value) == r
                and all(isinstance(row, list) and len(row) == c and all(map(_is_number, row))
                        for row in value)):
            raise wrong(f"a {r}x{c} matrix (list of {r} rows of {c} numbers)")
        return [[float(v) for v in row] for row in value]
    if t == "points":
        if not (isinstance(value, list) and all(
                isinstance(p, list) and len(p) == 2 and all(map(_is_number, p)) for p in value)):
            raise wrong("a list of [x, y] points")
        return [[float(v) for v in p] for p in value]
    raise AssertionError(f"schema: unknown type {t}")


def _join(path, key):
    return f"{path}.{key}" if path else key


def _check_semantics(cfg, source):
    """Rules that span keys (the same list as cpp/config.cpp)."""
    mesh = cfg["mesh"]
    needed = {"unit_square": ["n"], "gmsh": ["geometry", "size"], "xdmf": ["path"]}[mesh["type"]]
    for k in needed:
        if k not in mesh:
            raise ConfigError(f"{source}: mesh.{k}: missing required key for mesh.type "
                              f"\"{mesh['type']}\"")
    for k in mesh:
        if k not in needed + ["type", "diagonal"]:
            raise ConfigError(f"{source}: mesh.{k}: not used with mesh.type \"{mesh['type']}\"")
    mat = cfg["material"]
    _check_spd(mat["permittivity"], "material.permittivity", source,
               "permittivity must be positive definite (2.14c); the paper's Table 2 "
               "prints -beta, use +8.3 eps0 and +8.8 eps0")
    _check_spd(mat["viscosity"], "material.viscosity", source,
               "viscosity must be positive definite (2.11c)")
    _check_symmetric(mat["elastic"], "material.elastic", source)
    for name, bc in cfg["boundaries"].items():
        where = f"boundaries.{name}"
        if "displacement" in bc and ("traction" in bc or bc.get("contact")):
            raise ConfigError(f"{source}: {where}: a clamped boundary (displacement) "
                              "cannot also carry traction or contact")
        if "traction" in bc and bc.get("contact"):
            raise ConfigError(f"{source}: {where}: traction and contact are exclusive")
        if "potential" in bc and "surface_charge" in bc:
            raise ConfigError(f"{source}: {where}: potential and surface_charge are exclusive")
    _check_manufactured(cfg, source)


def _check_manufactured(cfg, source):
    """A manufactured solution brings its own loads and Dirichlet data;
    "exact" boundary values need one."""
    mms = "manufactured" in cfg
    unused = "not used with a manufactured solution (its loads come from the exact solution)"
    if mms:
        for key, zero in (("body_force", [0.0, 0.0]), ("charge_density", 0.0)):
            if cfg["loads"][key] != zero:
                raise ConfigError(f"{source}: loads.{key} = {_fmt(cfg['loads'][key])}: {unused}")
    for name, bc in cfg["boundaries"].items():
        for key in ("displacement", "potential"):
            if key not in bc:
                continue
            where = f"boundaries.{name}.{key} = {_fmt(bc[key])}"
            if bc[key] == "exact" and not mms:
                raise ConfigError(f"{source}: {where}: needs the key manufactured "
                                  "(the exact solution to take it from)")
            if bc[key] != "exact" and mms:
                raise ConfigError(f"{source}: {where}: with a manufactured solution the "
                                  "Dirichlet data are the exact solution's: use \"exact\"")
        for key in ("traction", "surface_charge"):
            if mms and key in bc:
                raise ConfigError(f"{source}: boundaries.{name}.{key}: {unused}")


def _check_symmetric(m, path, source):
    n = len(m)
    for i in range(n):
        for j in range(i + 1, n):
            if abs(m[i][j] - m[j][i]) > 1e-12 * max(abs(m[i][j]), abs(m[j][i]), 1e-300):
                raise ConfigError(f"{source}: {path} = {_fmt(m)}: must be symmetric "
                                  f"(entry [{i}][{j}] = {m[i][j]:g} but [{j}][{i}] = {m[j][i]:g})")


def _check_spd(m, path, source, why):
    _check_symmetric(m, path, source)
    # Sylvester's criterion on the leading minors (2x2 and 3x3 only)
    minors = [m[0][0], m[0][0] * m[1][1] - m[0][1] * m[1][0]]
    if len(m) == 3:
        minors.append(m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                      - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                      + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    if not all(d > 0 for d in minors):
        raise ConfigError(f"{source}: {path} = {_fmt(m)}: not positive definite: {why}")


def load(path, overrides=()):
    """Read, override, validate; return the effective config (defaults filled)."""
    source = str(path)
    try:
        text = Path(path).read_text()
    except OSError as err:
        raise ConfigError(f"{source}: cannot read config file: {err.strerror}") from None
    try:
        cfg = json.loads(text)
    except json.JSONDecodeError as err:
        raise ConfigError(f"{source}: invalid JSON at line {err.lineno} column {err.colno}: "
                          f"{err.msg}") from None
    return configure(cfg, overrides, source)


def configure(cfg, overrides, source):
    """Apply overrides to a config and validate it; errors name `source`."""
    for text in overrides:
        key, value = _parse_override(text, source)
        apply_override(cfg, key, value, source)
    schema = json.loads(SCHEMA_PATH.read_text())
    cfg = _check(cfg, schema, "", source)
    _check_semantics(cfg, source)
    return cfg
