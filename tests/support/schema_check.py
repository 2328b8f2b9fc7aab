#!/usr/bin/python3
"""Checks that schemas/scene.schema.json agrees with the C validator.

usage: schema_check.py SCHEMA --good FILE... --bad FILE...

Every --good file must validate.  Every --bad file must be rejected by the
schema too (or not even load as JSON), unless its name is in SEMANTIC_ONLY:
cases the C validator rejects for reasons a JSON Schema cannot express.
Prints one line per file; exits 1 when any check fails, 77 (skip) when the
jsonschema module is missing.
"""
import json
import os
import sys

# Bad scenes rejected only by the C validator (core/scene/parse*.c):
SEMANTIC_ONLY = {
    # crack geometry (core/scene/parse_cracks.c) and the particles it must cut
    "crack_polygon_in_2d",    # the form follows the scene's dimension
    "crack_segment_in_3d",
    "crack_not_convex",
    "crack_not_planar",
    "crack_zero_area",
    "crack_segment_zero_length",
    "crack_misses_body",      # needs the particles
    "thickness_axis_2d",      # fibres: 3-D uniform lattices only
    "thickness_axis_refined",
    "thickness_axis_radial_lattice",  # radial: a conforming cylinder only
    "thickness_regions_empty_box",    # thickness_regions: max > min per axis,
    "thickness_regions_no_particle",  # the particles of each region (disjoint,
    "thickness_regions_overlap",      # no gap along a fibre),
    "thickness_regions_gap",
    "thickness_regions_and_axis",     # not with a thickness_axis other than none
    "thickness_regions_tip_in_no_region",  # a listed tip: in one region's
    "thickness_regions_tip_ambiguous",     # fibres (needs the particles)
    "crack_growth_no_fibres",  # crack growth: a body with fibres, a pre-crack,
    "crack_growth_no_crack",   # a damage model, a tip at a crack's end
    "crack_growth_no_damage",
    "crack_growth_tip_off_crack",
    "crack_growth_criterion_no_voids",  # the material's quantities
    "crack_growth_initiate_no_damage",  # initiation: every thin body's material,
    "crack_growth_initiate_wide_fan",   # the fan with initiate,
    "crack_growth_no_tips",             # tips unless initiate (kept out of the schema)
    # JSON-level: Python's json module accepts these, jansson does not
    "duplicate_key",          # JSON_REJECT_DUPLICATES
    "huge_number",            # 1e400 overflows a double
    "nan_literal",            # NaN is not JSON
    # need the lattice
    "empty_geometry",         # no lattice point inside the geometry
    "absurd_particle_count",  # estimate > 10 x max_particles
    "bodies_candidates_in_all",  # the bodies' estimates together > 10 x max_particles
    "too_many_particles",     # actual count > max_particles
    # graded spacing (core/scene/refine.c): relative to the body's spacing and
    # geometry, or the count of the refined lattice
    "refine_finer_than_allowed",
    "refine_not_finer",
    "refine_region_outside",
    "refine_too_many_particles",
    "refine_conforming",
    # expression language (only the character set is in the schema)
    "expression_syntax",
    "expression_unknown_variable",
    "bad_selector_condition",
    "pressure_bad_expression",
    # cross references and uniqueness
    "unknown_material",
    "selector_unknown_body",
    "duplicate_body_names",
    "contact_one_body",       # a contact block needs two bodies
    "contact_bodies_overlap", # bodies in contact must not overlap at t = 0
    # geometry and vector consistency
    "wall_normal_zero",
    "notch_root_too_large",
    "box_max_below_min",
    # contradictions the particles reveal (core/bc/contradictions.c) and the
    # precision of positions far from the origin (core/scene/precision.c)
    "contradiction_fixed_velocity",
    "contradiction_two_velocities",
    "contradiction_wall_cuts_body",
    "pressure_normal_into_body",   # a pressure's normal against its body's surface
    "pressure_interior_particle",  # a pressure on a particle its neighbours surround
    "precision_far_from_origin",
    "precision_far_origin",
    # depend on "dimension"
    "cylinder_in_2d",
    "z_velocity_in_2d",
    "rigid_2d_velocity_off_plane",
    # strength parameters compared with each other or with the material's
    # youngs_modulus (a JSON Schema cannot compare two numbers of the instance)
    "yield_stress_above_youngs",          # yield_stress < E
    "swift_initial_yield_above_youngs",   # K eps_0^n < E
    "voce_saturation_below_yield",        # saturation_stress >= yield_stress
    "jc_melting_below_reference",         # melting_temperature > reference_temperature
    "jc_starts_molten",                   # thermal.initial_temperature < melting_temperature
    "damage_jc_melting_below_reference",  # damage melting_temperature > reference_temperature
    "damage_gtn_f0_above_critical",          # initial_void_fraction < critical_void_fraction
    "damage_gurson_f0_above_fracture",       # initial_void_fraction < fracture_void_fraction
    "damage_m_gurson_t1_above_t2",           # low_triaxiality < high_triaxiality
    "damage_gtn_critical_above_failure",     # critical_void_fraction < failure_void_fraction
    "damage_gtn_critical_above_inverse_q1",  # critical_void_fraction < 1/q1
    # virtual links: the treatment, the links block and the materials together
    # (core/scene/parse_links.c)
    "links_without_virtual_links",
    "virtual_links_without_links",
    "virtual_links_with_material_damage",
    "links_plastic_strain_elastic_material",
    # gauges and sections: cross references, uniqueness, the lattice
    "measures_gauge_unknown_group",
    "measures_gauge_same_group",
    "measures_gauge_wall_group",
    "measures_section_empty",
    "measures_section_normal_zero",
    "measures_section_duplicate_name",
    # the step count and the frame interval: estimated from the materials'
    # wave speeds, the spacings and the initial speeds (core/scene/check_steps.c)
    "step_count_cfl",
    "step_count_fixed",
    "step_longer_than_frame",
    # expressions evaluated over their domain (core/scene/check_values.c)
    "initial_velocity_division_by_zero",
    "initial_velocity_nan",
    "initial_velocity_log_zero",
    "initial_velocity_overflow",
    "initial_velocity_above_speed_limit",
    "velocity_bc_singular",
    "velocity_bc_log_zero",
    # rigid bodies (core/rigid/, core/scene/parse_rigid.c)
    "rigid_duplicate_name",            # uniqueness
    "rigid_overlaps_body",             # the particles at t = 0
    "rigid_cylinder_zero_axis",        # a direction's length
    "rigid_box_negative_half_size",    # c is ignored in 2-D, so > 0 depends on "dimension"
    "rigid_2d_box_rotated_about_x",    # depends on "dimension"
    "rigid_free_plane",                # motion compared with the shape
    # probes (core/scene/parse_measures.c, core/io/measures.c)
    "probe_duplicate_name",            # uniqueness
    "probe_selects_nothing",           # the particles at t = 0
    "probe_unknown_body",              # a name in /bodies
    # extents (core/scene/parse_measures.c, core/io/measures.c)
    "extent_selects_nothing",          # the particles at t = 0
    "extent_zero_axis",                # a direction's length
}


def main(argv):
    try:
        import jsonschema
    except ImportError:
        print("schema_check: python module jsonschema missing; skipped")
        return 77
    schema = json.load(open(argv[1]))
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    mode, failed = None, 0
    for arg in argv[2:]:
        if arg in ("--good", "--bad"):
            mode = arg
            continue
        name = os.path.splitext(os.path.basename(arg))[0]
        try:
            doc = json.load(open(arg))
        except ValueError as e:
            if mode == "--good":
                print(f"FAIL schema good {arg}: not JSON: {e}")
                failed += 1
            else:
                print(f"ok   schema bad  {name}: not JSON")
            continue
        errors = list(validator.iter_errors(doc))
        if mode == "--good":
            if errors:
                failed += 1
                e = errors[0]
                print(f"FAIL schema good {arg}: /{'/'.join(map(str, e.absolute_path))}: {e.message[:200]}")
            else:
                print(f"ok   schema good {arg}")
        elif name in SEMANTIC_ONLY:
            print(f"ok   schema bad  {name}: semantic only ({'rejected' if errors else 'accepted'} by the schema)")
        elif errors:
            print(f"ok   schema bad  {name}: rejected")
        else:
            failed += 1
            print(f"FAIL schema bad  {name}: the schema accepts it but the validator does not")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
