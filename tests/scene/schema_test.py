#!/usr/bin/python3
"""The scene schema (docs/scene.schema.json) against crankcheck's scene parser (scene/src/scene_file.cc).

The parser is the authority; the schema is what editors (taplo, Even Better TOML) check scenes with. This test keeps
the two from drifting apart:
- every example scene (scenes/*.toml), converted to JSON, is valid against the schema (and the parser accepts it);
- every key: the keys the parser allows in each table (it lists them when it refuses an unknown key) are exactly
  the schema's properties of that table;
- every limit: for each number with a minimum or maximum in the schema, a scene at the bound and one just beyond it
  (the next double, or the next integer) get the same verdict from the schema and from the parser, so a limit
  changed on one side only fails here; every bounded key of the schema has such a probe;
- a set of bad scenes: those the schema refuses are refused by the parser, and those the parser refuses are refused
  by the schema too, except for the rules the schema cannot express (cross-key rules), which must be listed in the
  schema's description;
- every key of every kind: each key of the schema (every table's properties, arrays of tables and array items
  included, found by walking the schema), in the first base scene that has it (HOSTS; a key that none has fails),
  set to integers (in, at and beyond its range, beyond 64 bits), the same as floats (2.0), floats with a fraction,
  NaN and infinities, strings, booleans, arrays and inline tables: both accept or both refuse, or the parser refuses
  by a cross-key rule that the schema's description lists (CROSS_KEY_RULES); and an integer and the float of the
  same value get the same verdict from each (an integer key takes 4.0 as 4, docs/SCENE-FORMAT.md).

Usage (ctest runs it, label unit): schema_test.py --schema docs/scene.schema.json --scenes scenes
--parser build/bin/scene_check. The parser is tests/scene/scene_check.cc, started without a shell, once for all
scenes (NUL-separated on stdin).

TOML to JSON: tables become objects, arrays arrays, integers and floats numbers. NaN and infinity, which JSON lacks,
become {"toml_float": "nan"} (or "inf", "-inf"): neither a number nor a string to the schema, as they are neither to
the parser; TOML dates and times become {"toml_datetime": ISO text}. An integer beyond 64 bits, which Python's tomllib
reads, is not TOML (TOML 1.0: "an error must be thrown"; toml++ refuses it), and so is refused by the schema's side.
"""

import argparse
import copy
import datetime
import json
import math
import pathlib
import subprocess
import sys
import tomllib
import unittest

import jsonschema

ARGS = None


# ----------------------------------------------------------------------------------------------------------------
# TOML <-> JSON


class NotToml(ValueError):
    """What tomllib reads but TOML does not allow."""


def to_json(value):
    """A TOML value (as tomllib reads it) as the JSON value the schema is checked on."""
    if isinstance(value, dict):
        return {k: to_json(v) for k, v in value.items()}
    if isinstance(value, list):
        return [to_json(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return {"toml_float": "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")}
    if isinstance(value, int) and not isinstance(value, bool) and not -2**63 <= value < 2**63:
        raise NotToml(f"integer {value} beyond 64 bits")
    if isinstance(value, (datetime.datetime, datetime.date, datetime.time)):
        return {"toml_datetime": value.isoformat()}
    return value


def toml_key(key):
    return key if key and all(c.isascii() and (c.isalnum() or c in "_-") for c in key) else json.dumps(key)


def toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)  # shortest round-trip form, valid TOML (1e-06, 1000000.0000000001, 5e-324)
    if isinstance(value, str):
        return json.dumps(value)  # JSON's escapes are TOML basic-string escapes
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):  # an inline table
        return "{" + ", ".join(f"{toml_key(k)} = {toml_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"no TOML form for {value!r}")


def dump_toml(scene):
    """A scene (dict of top-level values, tables and the `cylinder` array of tables) as TOML text."""
    lines = [f"{k} = {toml_value(v)}" for k, v in scene.items() if not isinstance(v, (dict, list))]
    for name, value in scene.items():
        if isinstance(value, dict):
            lines.append(f"[{name}]")
            lines += [f"{k} = {toml_value(v)}" for k, v in value.items()]
        elif isinstance(value, list) and value and all(isinstance(t, dict) for t in value):
            for table in value:
                lines.append(f"[[{name}]]")
                lines += [f"{k} = {toml_value(v)}" for k, v in table.items()]
        elif isinstance(value, list):
            lines.insert(0, f"{name} = {toml_value(value)}")
    return "\n".join(lines) + "\n"


# ----------------------------------------------------------------------------------------------------------------
# Scenes the cases are made from

PARTS = {
    "crank": {"radius": 0.05, "mass": 1.0, "com_radius": 0.02, "counterweight_mass": 0.9, "counterweight_radius": 0.03},
    "rod": {"length": 0.2, "mass": 0.5, "com_from_wrist_pin": 0.14, "inertia_about_wrist_pin": 0.012},
    "piston": {"mass": 0.4},
    "flywheel": {"inertia": 0.12},
}
INLINE = {"engine": {"cylinders": 2, "cycle": "four-stroke", "cylinder_angle_deg": 90, "speed_rpm": 3000}, **PARTS}
# Two-cylinder four-stroke: the phase angles are 0 and 720 / 2 = 360 degrees, so each cylinder fires at its ODC.
GAS = {**INLINE, "gas": {"bore": 0.08, "cycle_angle_deg": [0, 30, 360], "pressure_pa": [5e6, 1e6, 0.0],
                         "firing_order": [0, 1]}}
# An inline scene with a Lanchester pair.
SHAFTS = {**INLINE, "balance_shaft": [{"ratio": 2, "mass": 0.07, "radius": 0.04, "phase_deg": -90, "position": [0.04, -0.08, 0.0]},
                                      {"ratio": -2, "mass": 0.07, "radius": 0.04, "phase_deg": -90, "position": [-0.04, -0.08, 0.0]}]}
# Explicit throw angles, without gas (whose firing order would tie them to it).
INLINE_CRANK_ANGLES = {**INLINE, "engine": {**INLINE["engine"], "crank_angles_deg": [0, 360]}}
# Every key of an inline scene written out.
INLINE_FULL = {"format_version": 1, "name": "Twin, every key", "description": "Two cylinders,\n\"standing\".",
               "engine": {"cylinders": 2, "cycle": "four-stroke", "acting": "single", "crank_angles_deg": [0, 360],
                          "cylinder_angle_deg": 90, "cylinder_spacing": 0.09, "speed_rpm": 3000, "gravity": 9.80665,
                          "pin_offset": 0.0012},
               **PARTS, "gas": GAS["gas"]}
LAYOUT = {"engine": {"cycle": "four-stroke", "speed_rpm": 3000},
          "cylinder": [{"bank_angle_deg": 135, "throw_angle_deg": 90, "axial_position": 0.0},
                       {"bank_angle_deg": 45, "throw_angle_deg": 90, "axial_position": 0.02}], **PARTS}
# Each cylinder at its outer dead centre at its firing angle: theta_j = phi + throw_j - bank_j = 0.
LAYOUT_GAS = {"engine": {"cylinders": 2, "cycle": "four-stroke", "speed_rpm": 3000},
              "cylinder": [{"bank_angle_deg": 135, "throw_angle_deg": 90, "axial_position": 0.0, "firing_angle_deg": 45},
                           {"bank_angle_deg": 45, "throw_angle_deg": 90, "axial_position": 0.02,
                            "firing_angle_deg": -45}],
              **PARTS, "gas": {k: v for k, v in GAS["gas"].items() if k != "firing_order"}}

# Two inline cylinders (two throws) and a front mass: three sections of the crank train.
CRANKSHAFT = {**INLINE, "crankshaft": {"throw_inertia": 2e-3, "front_inertia": 4e-3, "stiffness": [4e5, 5.5e5, 7e5],
                                       "section_damping": 1.5, "throw_damping": 0.4}}
# The V twin of LAYOUT: both cylinders on one pin, one throw; no front mass: one section.
CRANKSHAFT_V = {**LAYOUT, "crankshaft": {"stiffness": [7e5]}}
# CRANKSHAFT with one damping per section (three sections).
CRANKSHAFT_DAMPING_LIST = {**INLINE, "crankshaft": {**CRANKSHAFT["crankshaft"], "section_damping": [1.5, 2.5, 0.0]}}
# LAYOUT with a desaxe offset on its second cylinder.
LAYOUT_PIN_OFFSET = {**LAYOUT, "cylinder": [LAYOUT["cylinder"][0], {**LAYOUT["cylinder"][1], "pin_offset": -0.0015}]}

DELETE = object()


def edit(base, *changes):
    """A copy of `base` with each (path, value) set; value DELETE removes the key. A path is a tuple of keys and
    indices, e.g. ("cylinder", 0, "bank_angle_deg")."""
    scene = copy.deepcopy(base)
    for path, value in changes:
        node = scene
        for key in path[:-1]:
            node = node[key]
        if value is DELETE:
            del node[path[-1]]
        else:
            node[path[-1]] = copy.deepcopy(value)
    return scene


# ----------------------------------------------------------------------------------------------------------------
# Cases: (name, TOML text, expectation). Expectations:
#   "valid"        both accept;
#   "invalid"      both refuse;
#   ("parser", R)  the parser refuses, the schema cannot express the rule: R must be listed in its description.

VALID, INVALID = "valid", "invalid"


def parser_only(rule):
    return ("parser", rule)


def cases():
    out = []

    def add(name, scene, expect):
        out.append((name, scene if isinstance(scene, str) else dump_toml(scene), expect))

    for name, scene in HOSTS:  # the base scenes, each valid
        add(name, scene, VALID)
    # Massless parts are real modelling choices; one cylinder may have any spacing (there is no second one).
    for table in ("crank", "rod", "piston"):
        add(f"{table}_massless", edit(INLINE, ((table, "mass"), 0)), VALID)
    add("counterweight_zero_without_radius", edit(INLINE, (("crank", "counterweight_mass"), 0),
                                                   (("crank", "counterweight_radius"), DELETE)), VALID)
    add("one_cylinder_any_spacing", edit(INLINE, (("engine", "cylinders"), 1), (("engine", "cylinder_spacing"), 1e300)),
        VALID)
    add("layout_without_axial", edit(LAYOUT, (("cylinder", 0, "axial_position"), DELETE),
                                     (("cylinder", 1, "axial_position"), DELETE)), VALID)
    add("two_stroke_gas", edit(GAS, (("engine", "cycle"), "two-stroke"), (("gas", "cycle_angle_deg"), [0, 30, 359.5])),
        VALID)
    add("double_acting", edit(INLINE, (("engine", "acting"), "double")), VALID)
    # An integer key takes a float with an integral value (JSON Schema cannot tell 2.0 from 2; SCENE-FORMAT.md).
    add("cylinders_as_float", edit(INLINE, (("engine", "cylinders"), 2.0)), VALID)
    add("cylinders_as_float_in_layout", edit(LAYOUT_GAS, (("engine", "cylinders"), 2.0)), VALID)
    add("format_version_as_float", edit(INLINE, (("format_version",), 1.0)), VALID)
    add("firing_order_as_floats", edit(GAS, (("gas", "firing_order"), [0.0, 1.0])), VALID)

    # Refused by both: the shape of the file.
    add("unknown_top_level_key", edit(INLINE, (("title",), "x")), INVALID)
    add("unknown_table", edit(INLINE, (("pistons",), {"mass": 1.0})), INVALID)
    for table in ("engine", "crank", "rod", "piston", "flywheel"):
        add(f"unknown_key_in_{table}", edit(INLINE, ((table, "colour"), "red")), INVALID)
    add("unknown_key_in_gas", edit(GAS, (("gas", "colour"), "red")), INVALID)
    add("unknown_key_in_cylinder", edit(LAYOUT, (("cylinder", 1, "firing_deg"), 0)), INVALID)
    add("pin_offset_per_cylinder", edit(LAYOUT, (("cylinder", 0, "pin_offset"), -0.0015)), VALID)
    add("balance_shafts", SHAFTS, VALID)
    add("balance_shaft_without_mass", edit(SHAFTS, (("balance_shaft", 1, "mass"), DELETE)), INVALID)
    add("balance_shaft_position_of_two", edit(SHAFTS, (("balance_shaft", 0, "position"), [0.0, 0.0])), INVALID)
    add("balance_shaft_unknown_key", edit(SHAFTS, (("balance_shaft", 0, "teeth"), 40)), INVALID)
    add("balance_shaft_ratio_fraction", edit(SHAFTS, (("balance_shaft", 0, "ratio"), 1.5)), INVALID)
    add("balance_shaft_ratio_tiny", edit(SHAFTS, (("balance_shaft", 0, "ratio"), 1e-300)), INVALID)
    add("balance_shaft_ratio_zero", edit(SHAFTS, (("balance_shaft", 0, "ratio"), 0)), parser_only("a balance shaft's ratio is nonzero"))
    # [crankshaft] (the elastic crank train): one stiffness per section, damping one value or one per section.
    add("crankshaft", CRANKSHAFT, VALID)
    add("crankshaft_v_pair_one_throw", CRANKSHAFT_V, VALID)
    add("crankshaft_defaults", edit(CRANKSHAFT, (("crankshaft", "front_inertia"), DELETE),
                                    (("crankshaft", "throw_inertia"), DELETE), (("crankshaft", "section_damping"), DELETE),
                                    (("crankshaft", "throw_damping"), DELETE), (("crankshaft", "stiffness"), [4e5, 5e5])),
        VALID)
    add("crankshaft_damping_list", edit(CRANKSHAFT, (("crankshaft", "section_damping"), [1, 2, 3])), VALID)
    add("crankshaft_unknown_key", edit(CRANKSHAFT, (("crankshaft", "teeth"), 3)), INVALID)
    add("crankshaft_without_stiffness", edit(CRANKSHAFT, (("crankshaft", "stiffness"), DELETE)), INVALID)
    add("crankshaft_stiffness_zero", edit(CRANKSHAFT, (("crankshaft", "stiffness", 1), 0)), INVALID)
    add("crankshaft_stiffness_negative", edit(CRANKSHAFT, (("crankshaft", "stiffness", 2), -7e5)), INVALID)
    add("crankshaft_stiffness_number", edit(CRANKSHAFT, (("crankshaft", "stiffness"), 4e5)), INVALID)
    add("crankshaft_stiffness_empty", edit(CRANKSHAFT, (("crankshaft", "stiffness"), [])), INVALID)
    add("crankshaft_throw_inertia_negative", edit(CRANKSHAFT, (("crankshaft", "throw_inertia"), -2e-3)), INVALID)
    add("crankshaft_section_damping_negative", edit(CRANKSHAFT, (("crankshaft", "section_damping"), -1.5)), INVALID)
    add("crankshaft_section_damping_empty", edit(CRANKSHAFT, (("crankshaft", "section_damping"), [])), INVALID)
    add("crankshaft_throw_damping_string", edit(CRANKSHAFT, (("crankshaft", "throw_damping"), "0.4")), INVALID)
    add("crankshaft_without_speed", edit(CRANKSHAFT, (("engine", "speed_rpm"), 0)), INVALID)
    add("crankshaft_is_a_value", edit(INLINE, (("crankshaft",), 2)), INVALID)
    add("crankshaft_stiffness_short", edit(CRANKSHAFT, (("crankshaft", "stiffness"), [4e5, 5e5])),
        parser_only("[crankshaft].stiffness has one value per section"))
    add("crankshaft_stiffness_per_cylinder_on_a_v_pin", edit(CRANKSHAFT_V, (("crankshaft", "stiffness"), [7e5, 7e5])),
        parser_only("[crankshaft].stiffness has one value per section"))
    add("crankshaft_section_damping_wrong_length", edit(CRANKSHAFT, (("crankshaft", "section_damping"), [1, 2])),
        parser_only("[crankshaft].section_damping is one value or one per section"))
    add("pin_offset_in_engine_with_cylinders", edit(LAYOUT, (("engine", "pin_offset"), 0.001)), INVALID)
    for table in ("engine", "crank", "rod", "piston"):
        add(f"missing_table_{table}", edit(INLINE, ((table,), DELETE)), INVALID)
    for table, keys in [("engine", ["cylinders", "cycle", "cylinder_angle_deg", "speed_rpm"]),
                        ("crank", ["radius", "mass", "com_radius", "counterweight_radius"]),
                        ("rod", ["length", "mass", "com_from_wrist_pin", "inertia_about_wrist_pin"]),
                        ("piston", ["mass"]), ("flywheel", ["inertia"])]:
        for key in keys:
            add(f"missing_{table}_{key}", edit(INLINE, ((table, key), DELETE)), INVALID)
    for key in ("bore", "cycle_angle_deg", "pressure_pa", "firing_order"):
        add(f"missing_gas_{key}", edit(GAS, (("gas", key), DELETE)), INVALID)
    for key in ("bank_angle_deg", "throw_angle_deg"):
        add(f"missing_cylinder_{key}", edit(LAYOUT, (("cylinder", 1, key), DELETE)), INVALID)
    add("missing_firing_angle", edit(LAYOUT_GAS, (("cylinder", 1, "firing_angle_deg"), DELETE)), INVALID)
    add("table_is_a_value", "engine = 3\n" + dump_toml({k: v for k, v in INLINE.items() if k != "engine"}), INVALID)
    add("cylinder_single_table", dump_toml({**LAYOUT, "cylinder": LAYOUT["cylinder"][0]}), INVALID)
    add("cylinder_empty_array", dump_toml(edit(LAYOUT, (("cylinder",), DELETE))) + "cylinder = []\n", INVALID)
    add("cylinders_65_tables", edit(LAYOUT, (("cylinder",), [{"bank_angle_deg": 90, "throw_angle_deg": 0}] * 65)),
        INVALID)
    add("not_toml", "this is = = not toml\n", INVALID)

    # Refused by both: types and enumerations.
    add("cylinders_string", edit(INLINE, (("engine", "cylinders"), "2")), INVALID)
    add("cylinders_fraction", edit(INLINE, (("engine", "cylinders"), 2.5)), INVALID)
    add("cylinders_float_above_64", edit(INLINE, (("engine", "cylinders"), 65.0)), INVALID)
    add("cylinders_float_beyond_any_integer", edit(INLINE, (("engine", "cylinders"), 1e300)), INVALID)
    add("cylinders_nan", edit(INLINE, (("engine", "cylinders"), math.nan)), INVALID)
    add("format_version_float_2", edit(INLINE, (("format_version",), 2.0)), INVALID)
    add("format_version_fraction", edit(INLINE, (("format_version",), 1.5)), INVALID)
    add("radius_string", edit(INLINE, (("crank", "radius"), "5 cm")), INVALID)
    add("mass_boolean", edit(INLINE, (("piston", "mass"), True)), INVALID)
    add("mass_array", edit(INLINE, (("piston", "mass"), [0.4])), INVALID)
    add("cycle_three_stroke", edit(INLINE, (("engine", "cycle"), "three-stroke")), INVALID)
    add("cycle_number", edit(INLINE, (("engine", "cycle"), 2)), INVALID)
    add("acting_triple", edit(INLINE, (("engine", "acting"), "triple")), INVALID)
    add("crank_angle_string", edit(INLINE, (("engine", "crank_angles_deg"), [0, "x"])), INVALID)
    add("crank_angles_not_array", edit(INLINE, (("engine", "crank_angles_deg"), 90)), INVALID)
    add("nan", edit(INLINE, (("rod", "mass"), math.nan)), INVALID)
    add("inf", edit(INLINE, (("crank", "radius"), math.inf)), INVALID)
    add("nan_spacing", edit(INLINE, (("engine", "cylinder_spacing"), math.nan)), INVALID)
    add("date", "speed = 1979-05-27\n" + dump_toml(INLINE), INVALID)
    add("speed_date", dump_toml(INLINE).replace("speed_rpm = 3000", "speed_rpm = 1979-05-27"), INVALID)
    add("format_version_2", edit(INLINE, (("format_version",), 2)), INVALID)
    add("format_version_0", edit(INLINE, (("format_version",), 0)), INVALID)
    add("format_version_string", edit(INLINE, (("format_version",), "1")), INVALID)
    add("name_number", edit(INLINE, (("name",), 4)), INVALID)
    add("description_array", edit(INLINE, (("description",), ["a", "b"])), INVALID)

    # Refused by both: rules between keys that the schema expresses (if/then, uniqueItems, prefixItems).
    add("counterweight_without_radius", edit(INLINE, (("crank", "counterweight_radius"), DELETE)), INVALID)
    for key, value in [("cylinder_angle_deg", 90), ("crank_angles_deg", [0, 0]), ("cylinder_spacing", 0.1)]:
        add(f"layout_with_{key}", edit(LAYOUT, (("engine", key), value)), INVALID)
    add("axial_for_some", edit(LAYOUT, (("cylinder", 1, "axial_position"), DELETE)), INVALID)
    add("gas_double_acting", edit(GAS, (("engine", "acting"), "double")), INVALID)
    add("firing_order_with_layout", edit(LAYOUT_GAS, (("gas", "firing_order"), [0, 1])), INVALID)
    add("firing_angle_without_gas", edit(LAYOUT, (("cylinder", 0, "firing_angle_deg"), 45)), INVALID)
    add("firing_order_repeats", edit(GAS, (("gas", "firing_order"), [0, 0])), INVALID)
    add("firing_order_negative", edit(GAS, (("gas", "firing_order"), [0, -1])), INVALID)
    add("firing_order_fraction", edit(GAS, (("gas", "firing_order"), [0, 1.5])), INVALID)
    add("firing_order_float_repeats", edit(GAS, (("gas", "firing_order"), [1.0, 1])), INVALID)
    add("cycle_angles_start_late", edit(GAS, (("gas", "cycle_angle_deg"), [5, 30, 360])), INVALID)
    add("cycle_angles_empty", edit(GAS, (("gas", "cycle_angle_deg"), []), (("gas", "pressure_pa"), [])), INVALID)
    add("two_stroke_cycle_angle_360", edit(GAS, (("engine", "cycle"), "two-stroke"),
                                              (("gas", "cycle_angle_deg"), [0, 30, 360])), INVALID)

    # Refused by the parser only: rules the schema cannot express (each listed in the schema's description).
    add("lambda_one", edit(INLINE, (("crank", "radius"), 0.2)), parser_only("lambda = r / l < 1"))
    add("com_beyond_rod", edit(INLINE, (("rod", "com_from_wrist_pin"), 0.25)), parser_only("z_k <= l"))
    add("inertia_below_point_mass", edit(INLINE, (("rod", "inertia_about_wrist_pin"), 0.009)),
        parser_only("I_o >= m_k z_k^2"))
    add("crank_angles_wrong_length", edit(INLINE, (("engine", "crank_angles_deg"), [0, 90, 180])),
        parser_only("crank_angles_deg has one angle per cylinder"))
    add("layout_count_differs", edit(LAYOUT, (("engine", "cylinders"), 3)),
        parser_only("[engine].cylinders equals the number of [[cylinder]] tables"))
    add("firing_order_index_beyond_k", edit(GAS, (("gas", "firing_order"), [0, 2])),
        parser_only("firing_order lists each cylinder 0..k-1 once"))
    add("firing_order_too_long", edit(GAS, (("gas", "firing_order"), [0, 1, 2])),
        parser_only("firing_order lists each cylinder 0..k-1 once"))
    add("spacing_too_long", edit(INLINE, (("engine", "cylinder_spacing"), 2e6)),
        parser_only("|cylinder_spacing| (k - 1) <= 1e6 m"))
    # l - r = 0.15 m in these scenes.
    add("pin_offset_beyond_l_minus_r", edit(INLINE, (("engine", "pin_offset"), -0.16)),
        parser_only("|pin_offset| < l - r"))
    add("pin_offset_of_a_cylinder_beyond_l_minus_r", edit(LAYOUT, (("cylinder", 1, "pin_offset"), 0.16)),
        parser_only("|pin_offset| < l - r"))
    add("cycle_angles_decrease", edit(GAS, (("gas", "cycle_angle_deg"), [0, 30, 20])),
        parser_only("cycle_angle_deg strictly increasing"))
    add("pressures_short", edit(GAS, (("gas", "pressure_pa"), [5e6, 1e6])),
        parser_only("pressure_pa has one pressure per cycle angle"))
    add("pressures_in_bar", edit(GAS, (("gas", "pressure_pa"), [50.0, 10.0, 0.0])),
        parser_only("the largest |pressure_pa| at least 1e4 Pa"))
    add("firing_away_from_dead_centre", edit(LAYOUT_GAS, (("cylinder", 1, "firing_angle_deg"), 50)),
        parser_only("each cylinder at its outer dead centre at its firing angle"))
    add("throw_far_from_bank", edit(LAYOUT, (("cylinder", 1, "bank_angle_deg"), -1e6)),
        parser_only("|throw_angle_deg - bank_angle_deg| <= 1e6 deg"))
    return out


# ----------------------------------------------------------------------------------------------------------------
# Limits: every bound of the schema probed against the parser

def probe_scenes():
    """For each bounded number of the schema (a path with "[]" for array items): a function (value, side) -> the
    scene with that value where the bound can be reached, side "low" or "high" (the other keys made compatible:
    e.g. r close to 1e6 needs l = 1e6)."""
    def at(base, path, *extra):
        return lambda v, side: edit(base, *extra, (path, v))

    k64 = (("engine", "cylinders"), 64)
    firing_64 = [0] + list(range(63, 0, -1))  # [0, k-1, ..., 1]: valid for every k and stroke (SCENE-FORMAT.md)
    big_rod = ((("rod", "length"), 1e6), (("rod", "inertia_about_wrist_pin"), 1e13))
    return {
        ("format_version",): at(INLINE, ("format_version",)),
        ("engine", "cylinders"): at(INLINE, ("engine", "cylinders")),
        ("engine", "crank_angles_deg", "[]"): at(INLINE, ("engine", "crank_angles_deg", 1),
                                                  (("engine", "crank_angles_deg"), [0, 0])),
        ("engine", "cylinder_angle_deg"): at(INLINE, ("engine", "cylinder_angle_deg")),
        ("engine", "speed_rpm"): at(INLINE, ("engine", "speed_rpm")),
        ("engine", "gravity"): at(INLINE, ("engine", "gravity")),
        # r < l <= 1e6: near its upper bound r needs the longest rod.
        ("crank", "radius"): lambda v, side: edit(INLINE, (("crank", "radius"), v),
                                                  *(big_rod if side == "high" else ())),
        ("crank", "mass"): at(INLINE, ("crank", "mass")),
        ("crank", "com_radius"): at(INLINE, ("crank", "com_radius")),
        ("crank", "counterweight_mass"): at(INLINE, ("crank", "counterweight_mass")),
        ("crank", "counterweight_radius"): at(INLINE, ("crank", "counterweight_radius")),
        # l > r >= 1e-6 and z_k <= l: near its lower bound l needs the smallest crank and z_k = 0.
        ("rod", "length"): lambda v, side: edit(INLINE, (("rod", "length"), v), *(
            ((("crank", "radius"), 1e-6), (("rod", "com_from_wrist_pin"), 0)) if side == "low" else ())),
        # I_o >= m_k z_k^2: with z_k = 0 any mass fits.
        ("rod", "mass"): at(INLINE, ("rod", "mass"), (("rod", "com_from_wrist_pin"), 0)),
        ("rod", "com_from_wrist_pin"): lambda v, side: edit(INLINE, (("rod", "com_from_wrist_pin"), v),
                                                            *(big_rod if side == "high" else ())),
        ("rod", "inertia_about_wrist_pin"): at(INLINE, ("rod", "inertia_about_wrist_pin"),
                                               (("rod", "com_from_wrist_pin"), 0)),
        ("piston", "mass"): at(INLINE, ("piston", "mass")),
        ("flywheel", "inertia"): at(INLINE, ("flywheel", "inertia")),
        ("gas", "bore"): at(GAS, ("gas", "bore")),
        ("gas", "cycle_angle_deg", "[]"): at(GAS, ("gas", "cycle_angle_deg", 2)),
        ("gas", "pressure_pa", "[]"): at(GAS, ("gas", "pressure_pa", 1)),
        # Index 0 holds the smallest cylinder (0), index 1 the largest (k - 1 = 63): [0, 63, 62, ..., 1].
        ("gas", "firing_order", "[]"): lambda v, side: edit(
            GAS, k64, (("gas", "firing_order"), firing_64), (("gas", "firing_order", 0 if side == "low" else 1), v)),
        # |throw - bank| <= 1e6 deg as well: the other angle of the cylinder follows, up to the bound.
        ("cylinder", "[]", "bank_angle_deg"): lambda v, side: edit(
            LAYOUT, (("cylinder", 0, "throw_angle_deg"), max(-1e6, min(1e6, v))), (("cylinder", 0, "bank_angle_deg"), v)),
        ("cylinder", "[]", "throw_angle_deg"): lambda v, side: edit(
            LAYOUT, (("cylinder", 0, "bank_angle_deg"), max(-1e6, min(1e6, v))), (("cylinder", 0, "throw_angle_deg"), v)),
        ("cylinder", "[]", "axial_position"): at(LAYOUT, ("cylinder", 0, "axial_position")),
        ("crankshaft", "throw_inertia"): at(CRANKSHAFT, ("crankshaft", "throw_inertia")),
        # front_inertia = 0 (and below) means no front mass: one section fewer.
        ("crankshaft", "front_inertia"): lambda v, side: edit(
            CRANKSHAFT, (("crankshaft", "front_inertia"), v), *(
                ((("crankshaft", "stiffness"), [4e5, 5e5]),) if side == "low" else ())),
        ("crankshaft", "stiffness", "[]"): at(CRANKSHAFT, ("crankshaft", "stiffness", 1)),
        ("crankshaft", "section_damping"): at(CRANKSHAFT, ("crankshaft", "section_damping")),
        ("crankshaft", "section_damping", "[]"): at(CRANKSHAFT, ("crankshaft", "section_damping", 1),
                                                    (("crankshaft", "section_damping"), [1, 2, 3])),
        ("crankshaft", "throw_damping"): at(CRANKSHAFT, ("crankshaft", "throw_damping")),
        ("balance_shaft", "[]", "ratio"): at(SHAFTS, ("balance_shaft", 0, "ratio")),
        ("balance_shaft", "[]", "mass"): at(SHAFTS, ("balance_shaft", 0, "mass")),
        ("balance_shaft", "[]", "radius"): at(SHAFTS, ("balance_shaft", 0, "radius")),
        ("balance_shaft", "[]", "position", "[]"): at(SHAFTS, ("balance_shaft", 0, "position", 1)),
        ("balance_shaft", "[]", "phase_deg"): at(SHAFTS, ("balance_shaft", 0, "phase_deg")),
        # At its firing angle F the cylinder must be at its outer dead centre: F + throw - bank = 0 (mod 360).
        # 1e6 = 2778 x 360 - 80, so throw - bank = 80 at the upper bound and -80 at the lower.
        ("cylinder", "[]", "firing_angle_deg"): lambda v, side: edit(
            LAYOUT_GAS, (("cylinder", 0), {"bank_angle_deg": 0, "throw_angle_deg": 80 if side == "high" else -80,
                                           "axial_position": 0.0, "firing_angle_deg": v})),
    }


def resolve(schema, node):
    while "$ref" in node:
        ref = node["$ref"]
        assert ref.startswith("#/$defs/"), ref
        merged = {k: v for k, v in node.items() if k != "$ref"}
        node = {**schema["$defs"][ref[len("#/$defs/"):]], **merged}
    return node


def bounded_numbers(schema, node=None, path=()):
    """{path: [(keyword, bound, is_integer)]} for every number with a minimum or maximum, through properties,
    items, $ref and anyOf (the conditionals of allOf are checked by the bad scenes)."""
    node = resolve(schema, schema if node is None else node)
    found = {}
    bounds = [(kw, node[kw]) for kw in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum") if kw in node]
    if bounds:
        found.setdefault(path, []).extend((kw, b, node.get("type") == "integer") for kw, b in bounds)
    for branch in node.get("anyOf", []):
        for p, b in bounded_numbers(schema, branch, path).items():
            found.setdefault(p, []).extend(b)
    for key, sub in node.get("properties", {}).items():
        found.update(bounded_numbers(schema, sub, path + (key,)))
    if isinstance(node.get("items"), dict):
        for p, b in bounded_numbers(schema, node["items"], path + ("[]",)).items():
            found.setdefault(p, []).extend(b)
    return found


def probe_values(keyword, bound, is_integer):
    """(value, side, expected verdict): the bound itself and the next value beyond it."""
    def beyond(direction):
        return bound + direction if is_integer else math.nextafter(bound, direction * math.inf)
    return {
        "minimum": [(bound, "low", VALID), (beyond(-1), "low", INVALID)],
        "maximum": [(bound, "high", VALID), (beyond(+1), "high", INVALID)],
        "exclusiveMinimum": [(bound, "low", INVALID), (beyond(+1), "low", VALID)],
        "exclusiveMaximum": [(bound, "high", INVALID), (beyond(-1), "high", VALID)],
    }[keyword]


# ----------------------------------------------------------------------------------------------------------------
# Every key of the schema, with a value of every kind, against the parser

# The base scenes a key's probes are placed in, in this order of preference: each key of the schema (and each array
# item) is probed in the first scene that has it, where its own value is valid, so that the rest of the scene is
# valid for it. A key of the schema that none of them has fails test_every_key_takes_every_kind_of_value: give it,
# with a valid value, to one of them.
HOSTS = [("inline", INLINE), ("inline_crank_angles", INLINE_CRANK_ANGLES), ("inline_every_key", INLINE_FULL),
         ("gas", GAS), ("layout", LAYOUT), ("layout_gas", LAYOUT_GAS), ("layout_pin_offset", LAYOUT_PIN_OFFSET),
         ("crankshaft", CRANKSHAFT), ("crankshaft_damping_list", CRANKSHAFT_DAMPING_LIST),
         ("crankshaft_v", CRANKSHAFT_V), ("shafts", SHAFTS)]

# The parser's refusals by the cross-key rules that the schema cannot express: a fragment of the parser's message
# and the rule as the schema's description lists it. A probe that the schema accepts may be refused by the parser
# only with one of these (a value of one key that breaks a rule with another, e.g. [crank].radius = 1 against the
# base scene's 0.2 m rod).
CROSS_KEY_RULES = {
    "lambda = r / l must be < 1": "lambda = r / l < 1",
    "must lie on the rod, 0 <= z_k <= l": "z_k <= l",
    "must be >= m_k z_k^2": "I_o >= m_k z_k^2",
    "must have one angle per cylinder": "crank_angles_deg has one angle per cylinder",
    "must equal the number of [[cylinder]] tables": "[engine].cylinders equals the number of [[cylinder]] tables",
    "throw_angle_deg - bank_angle_deg must be at most": "|throw_angle_deg - bank_angle_deg| <= 1e6 deg",
    "must be a cylinder index 0..": "firing_order lists each cylinder 0..k-1 once",
    "must list each of the": "firing_order lists each cylinder 0..k-1 once",
    "must keep every cylinder within": "|cylinder_spacing| (k - 1) <= 1e6 m",
    "|pin_offset| must be < l - r": "|pin_offset| < l - r",
    "must be nonzero and at most 64 in magnitude": "a balance shaft's ratio is nonzero",
    "one per section from front to flywheel": "[crankshaft].stiffness has one value per section",
    "must be one value for all sections, or a list of": "[crankshaft].section_damping is one value or one per section",
    "must be strictly increasing": "cycle_angle_deg strictly increasing",
    "must have one pressure per cycle angle": "pressure_pa has one pressure per cycle angle",
    "below 1e4 Pa (0.1 bar)": "the largest |pressure_pa| at least 1e4 Pa",
    "is not at its outer dead centre at its firing angle": "each cylinder at its outer dead centre at its firing angle",
}


def schema_keys(schema, node=None, path=()):
    """{path: node} for every key of the schema at any depth (properties; "[]" for an array's items, arrays of
    tables included), through $ref and anyOf (the conditionals of allOf add no keys)."""
    node = resolve(schema, schema if node is None else node)
    found = {path: node} if path else {}
    for branch in node.get("anyOf", []):
        for p, n in schema_keys(schema, branch, path).items():
            if p != path:
                found.setdefault(p, n)
    for key, sub in node.get("properties", {}).items():
        for p, n in schema_keys(schema, sub, path + (key,)).items():
            found.setdefault(p, n)
    if isinstance(node.get("items"), dict):
        for p, n in schema_keys(schema, node["items"], path + ("[]",)).items():
            found.setdefault(p, n)
    return found


def locate(scene, path):
    """Where the schema path is in the scene, as keys and indices ("[]": the last item that has the rest), or None."""
    if not path:
        return ()
    head, rest = path[0], path[1:]
    if head == "[]":
        for i in reversed(range(len(scene)) if isinstance(scene, list) else []):
            if (sub := locate(scene[i], rest)) is not None:
                return (i,) + sub
        return None
    if isinstance(scene, dict) and head in scene and (sub := locate(scene[head], rest)) is not None:
        return (head,) + sub
    return None


def value_at(scene, where):
    for key in where:
        scene = scene[key]
    return scene


def integer_range(schema, node):
    """(lo, hi): the smallest and the largest integer the node's numbers allow (None: unbounded on that side), or
    None where it takes no number; through anyOf (a mass: 0, or 1e-9 .. 1e6)."""
    ranges = []
    for branch in [node] + [resolve(schema, b) for b in node.get("anyOf", [])]:
        if isinstance(branch.get("const"), (int, float)) and not isinstance(branch["const"], bool):
            ranges.append((math.ceil(branch["const"]), math.floor(branch["const"])))
        elif branch.get("type") in ("number", "integer"):
            lows = [math.ceil(branch["minimum"])] if "minimum" in branch else []
            lows += [math.floor(branch["exclusiveMinimum"]) + 1] if "exclusiveMinimum" in branch else []
            highs = [math.floor(branch["maximum"])] if "maximum" in branch else []
            highs += [math.ceil(branch["exclusiveMaximum"]) - 1] if "exclusiveMaximum" in branch else []
            ranges.append((max(lows, default=None), min(highs, default=None)))
    if not ranges:
        return None
    lo = None if any(r[0] is None for r in ranges) else min(r[0] for r in ranges)
    hi = None if any(r[1] is None for r in ranges) else max(r[1] for r in ranges)
    return lo, hi


def every_kind_of_value(schema, node, base):
    """[(kind, value)] for one key whose value in its base scene is `base`: integers (the base value rounded into
    the key's range, the ends of the range, 0, 1, 2, one beyond each end, beyond 64 bits) and each as a float; floats
    with a fraction next to it, huge, NaN and infinities; strings, booleans, arrays, inline tables; the base value
    itself."""
    numeric = isinstance(base, (int, float)) and not isinstance(base, bool)
    lo, hi = integer_range(schema, node) or (None, None)
    n0 = round(base) if numeric else 2
    n0 = max(n0, lo) if lo is not None else n0
    n0 = min(n0, hi) if hi is not None else n0
    integers = {n0, 0, 1, 2, 2**63, -2**63 - 1}
    integers |= {lo, lo - 1} if lo is not None else set()
    integers |= {hi, hi + 1} if hi is not None else set()
    values = [("base", base)]
    for n in sorted(integers):
        values += [("integer", n), ("integral float", float(n))]
    values += [("integral float", x) for x in (-0.0, 1e300, -1e300)]
    values += [("fraction", x) for x in (n0 + 0.5, n0 - 0.5, math.nextafter(float(n0), math.inf),
                                         math.nextafter(float(n0), -math.inf))]
    values += [("non-finite", x) for x in (math.nan, math.inf, -math.inf)]
    values += [("string", x) for x in ("x", "2", "")] + [("bool", True), ("bool", False)]
    values += [("array", x) for x in ([], [base], ["x"])] + [("inline table", x) for x in ({}, {"a": 1})]
    seen, unique = set(), []
    for kind, value in values:
        if (id_ := (type(value).__name__, repr(value))) not in seen:
            seen.add(id_)
            unique.append((kind, value))
    return unique


# ----------------------------------------------------------------------------------------------------------------


def run_parser(texts):
    """The parser's verdict on each text: ("ok", "") or ("refused", message)."""
    result = subprocess.run([ARGS.parser], input="\0".join(texts).encode(), capture_output=True, check=False)
    lines = result.stdout.decode().splitlines()
    if result.returncode != 0 or len(lines) != len(texts):
        raise RuntimeError(f"scene_check failed (status {result.returncode}):\n{result.stdout.decode()}"
                           f"{result.stderr.decode()}")
    return [tuple((line.split("\t", 1) + [""])[:2]) for line in lines]


class SchemaTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.schema = json.loads(pathlib.Path(ARGS.schema).read_text())
        jsonschema.Draft202012Validator.check_schema(cls.schema)
        cls.validator = jsonschema.Draft202012Validator(cls.schema)

    def schema_verdict(self, text):
        try:
            document = to_json(tomllib.loads(text))
        except (tomllib.TOMLDecodeError, NotToml) as e:
            return INVALID, f"not TOML ({e})"
        errors = sorted(self.validator.iter_errors(document), key=lambda e: list(e.absolute_path))
        if errors:
            return INVALID, "; ".join(f"{'/'.join(map(str, e.absolute_path))}: {e.message}"[:200] for e in errors)
        return VALID, ""

    def check(self, named_cases):
        """named_cases: (name, text, expectation); asserts both verdicts."""
        verdicts = run_parser([text for _, text, _ in named_cases])
        for (name, text, expect), (parser, message) in zip(named_cases, verdicts):
            with self.subTest(name):
                schema, why = self.schema_verdict(text)
                parser_says = VALID if parser == "ok" else INVALID
                if isinstance(expect, tuple):
                    self.assertEqual(parser_says, INVALID, f"the parser accepts:\n{text}")
                    self.assertEqual(schema, VALID, f"the schema refuses ({why}): move the case to INVALID")
                    self.assertIn(expect[1], self.schema["description"],
                                  "a rule the schema cannot express is listed in its description")
                else:
                    self.assertEqual(parser_says, expect, f"parser: {message or 'accepts'}\n{text}")
                    self.assertEqual(schema, expect, f"schema: {why or 'accepts'}\n{text}")

    def test_every_example_scene_is_valid(self):
        scenes = sorted(pathlib.Path(ARGS.scenes).glob("*.toml"))
        self.assertGreaterEqual(len(scenes), 5)
        self.check([(path.name, path.read_text(), VALID) for path in scenes])
        for path in scenes:
            with self.subTest(path.name):
                text = path.read_text()
                self.assertTrue(text.startswith("#:schema ../docs/scene.schema.json\n"),
                                "each example scene names the schema for editors (taplo's directive)")
                self.assertIn("format_version = 1", text)

    def test_parser_and_schema_agree_on_bad_scenes(self):
        self.check(cases())

    def test_every_limit_agrees(self):
        bounded = bounded_numbers(self.schema)
        probes = probe_scenes()
        self.assertEqual(sorted(bounded), sorted(probes), "every bounded number of the schema has a probe")
        named = []
        for path, bounds in sorted(bounded.items()):
            for keyword, bound, is_integer in bounds:
                for value, side, expect in probe_values(keyword, bound, is_integer):
                    named.append((f"{'.'.join(path)} {keyword} {value!r}", dump_toml(probes[path](value, side)), expect))
        self.assertGreater(len(named), 50)
        self.check(named)

    def test_every_key_takes_every_kind_of_value(self):
        """Every key of the schema (and every array item), in the first base scene that has it, set to a value of
        every kind (every_kind_of_value): the schema and the parser agree, or the parser refuses by a cross-key rule
        that the schema's description lists; an integer and the float of the same value get the same verdict from
        each."""
        keys = schema_keys(self.schema)
        hosted = {path: next(((name, base, where) for name, base in HOSTS
                              if (where := locate(base, path)) is not None), None) for path in keys}
        self.assertEqual([".".join(path) for path, host in hosted.items() if host is None], [],
                         "keys of the schema that no base scene (HOSTS) has: give each, with a valid value, to one")
        for rule in set(CROSS_KEY_RULES.values()):
            self.assertIn(rule, self.schema["description"], "a cross-key rule is listed in the schema's description")
        probes = []  # (key, kind, value, host, text)
        for path, (host, base, where) in sorted(hosted.items()):
            for kind, value in every_kind_of_value(self.schema, keys[path], value_at(base, where)):
                probes.append((".".join(path), kind, value, host, dump_toml(edit(base, (where, value)))))
        self.assertGreater(len(probes), 20 * len(keys))
        verdicts = run_parser([text for *_, text in probes])
        seen = {}  # (key, host, an integral value) -> {"int" or "float": (schema's verdict, parser's, why)}
        for (key, kind, value, host, text), (parser, message) in zip(probes, verdicts):
            with self.subTest(f"{key} = {value!r} ({kind}) in {host}"):
                schema, why = self.schema_verdict(text)
                parser_says = VALID if parser == "ok" else INVALID
                if (type(value) in (int, float) and math.isfinite(value) and value == int(value)
                        and -2**63 <= value < 2**63 and float(value) == value):  # the base value too
                    seen.setdefault((key, host, value), {})[type(value).__name__] = (schema, parser_says, message or why)
                if schema == VALID and parser_says == INVALID:
                    rules = [rule for fragment, rule in CROSS_KEY_RULES.items() if fragment in message]
                    self.assertTrue(rules, f"the schema accepts, the parser refuses by no listed cross-key rule: "
                                           f"{message}\n{text}")
                else:
                    self.assertEqual(parser_says, schema, f"schema: {why or 'accepts'}; parser: {message or 'accepts'}"
                                                          f"\n{text}")
        pairs = {k: v for k, v in seen.items() if len(v) == 2}
        self.assertGreater(len(pairs), 4 * len(keys))
        for (key, host, value), kinds in sorted(pairs.items(), key=repr):
            with self.subTest(f"{key} = {value!r} and {float(value)!r} in {host}"):
                self.assertEqual(kinds["int"][:2], kinds["float"][:2],
                                 f"(schema, parser) for the integer and the float: {kinds}")

    def test_keys_are_those_the_parser_allows(self):
        """The parser lists the allowed keys when it refuses an unknown one: the schema's properties are the same."""
        def allowed(scene, prefix):
            ((verdict, message),) = run_parser([dump_toml(scene)])
            self.assertEqual(verdict, "refused")
            listed = message.split("(", 1)[1].rstrip(")")
            self.assertTrue(message.startswith(f"scene.toml: {prefix}"), message)
            return listed
        props = self.schema["properties"]
        for table, base in [("engine", INLINE), ("crank", INLINE), ("rod", INLINE), ("piston", INLINE),
                            ("flywheel", INLINE), ("gas", GAS), ("crankshaft", CRANKSHAFT)]:
            with self.subTest(table):
                listed = allowed(edit(base, ((table, "zz_unknown"), 1)), f"[{table}].zz_unknown")
                self.assertEqual(sorted(listed.removeprefix("allowed: ").split(", ")),
                                 sorted(props[table]["properties"]))
        with self.subTest("cylinder"):
            listed = allowed(edit(LAYOUT, (("cylinder", 0, "zz_unknown"), 1)), "cylinder[0].zz_unknown")
            self.assertEqual(sorted(listed.removeprefix("allowed: ").split(", ")),
                             sorted(props["cylinder"]["items"]["properties"]))
        with self.subTest("top level"):
            listed = allowed(edit(INLINE, (("zz_unknown",), 1)), "zz_unknown")
            top, tables = listed.removeprefix("top level: ").split("; tables: ")
            names = top.split(", ") + [t.strip("[]") for t in tables.split(", ")]
            self.assertEqual(sorted(names), sorted(props))

    def test_every_key_has_a_description_with_its_unit_or_values(self):
        def leaves(node, path):
            node = resolve(self.schema, node)
            yield path, node
            for key, sub in node.get("properties", {}).items():
                yield from leaves(sub, path + (key,))
            if isinstance(node.get("items"), dict):
                yield from leaves(node["items"], path + ("[]",))
        for path, node in leaves(self.schema, ()):
            if path and path[-1] != "[]":
                with self.subTest(".".join(path)):
                    self.assertIn("description", node)
                    if node.get("type") == "number":
                        self.assertRegex(node["description"], r"\[(m|kg|kg m\^2|deg|rpm|m/s\^2|Pa|N m/rad|N m s/rad|-)\]",
                                         "a number's description gives its unit")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--schema", required=True)
    parser.add_argument("--scenes", required=True)
    parser.add_argument("--parser", required=True, help="the scene_check program")
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=1)
