#!/usr/bin/env python3
"""Fuzz test of TissueFEM's input checking.

Usage: python3 tests/fuzz/fuzz_inputs.py TISSUEFEM_EXE REPO_ROOT WORK_DIR

Generates mutated copies of the shipped scenes (parameters/*.prm) and meshes
(data/liver.msh, parameters/meshes/jeffrey_muscle.vtu), each of which is
certainly invalid input, and runs TISSUEFEM_EXE on each. Every case must

  - exit with status 2 (bad input) within TIMEOUT seconds (a hang is killed
    and counts as a failure),
  - print exactly one non-empty line on stderr, starting with
    "tissuefem: error:" (mesh cases: naming the mutated mesh file),
  - leave no file behind: the run's working directory (a fresh empty
    directory) must still be empty afterwards, and nothing may appear beside
    the mutated input.

Before the cases, "control" runs check that the unmutated scenes (with the
same rewrites: absolute mesh paths, output directory inside the run's
directory) and the mesh scene template on the unmutated meshes pass
`tissuefem --validate`, so that each case's error comes from its mutation.

Each case's input is kept in WORK_DIR/<case-name>/ (the run's working
directory is WORK_DIR/<case-name>/cwd/). WORK_DIR is deleted and recreated at
the start. Prints one line per case, a final count, and exits 1 if any case
(or control) failed. Standard library only; deterministic (seeded).
"""

import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

SEED = 20261123
TIMEOUT = 60            # seconds per run
EXE_WAIT = 600          # seconds to wait for a missing executable (rebuild)
ERROR_PREFIX = "tissuefem: error:"

OUTPUT_BLOCK = "subsection Output\n  set Directory = out\n  set Summary file = \nend\n"


# ---------------------------------------------------------------------------
# Cases


class Case:
    """One input that must be rejected.

    files: {file name: bytes} written into WORK_DIR/<name>/;
    prm: the file name passed to tissuefem;
    must_name: substrings the error line must contain (a failure if not);
    should_name: a substring the error line is expected to contain (only a
    note if not: the README promises a line 'naming the parameter or file').
    """

    def __init__(self, kind, name, files, prm, must_name=(), should_name=None,
                 args=()):
        self.kind = kind
        self.name = name
        self.files = files
        self.prm = prm
        self.must_name = list(must_name)
        self.should_name = should_name
        self.args = list(args)


# ---------------------------------------------------------------------------
# Parameter-file helpers

SET_RE = re.compile(r"^(\s*set\s+)(.*?)(\s*=\s*)(.*?)\s*$", re.IGNORECASE)


def absolutize_mesh_paths(text, scene_dir):
    """Relative 'Mesh file' (and 'Trajectory file') values become absolute,
    relative to the scene's directory, as tissuefem would take them."""
    out = []
    for line in text.split("\n"):
        m = SET_RE.match(line)
        if m and m.group(2) in ("Mesh file", "Trajectory file"):
            value = m.group(4)
            if value and not os.path.isabs(value):
                value = os.path.normpath(os.path.join(scene_dir, value))
                line = m.group(1) + m.group(2) + m.group(3) + value
        out.append(line)
    return "\n".join(out)


def rewrite_output_lines(text):
    """Points an existing Output/Directory into the run's directory and
    empties an existing Summary file (done before every mutation)."""
    out = []
    for line in text.split("\n"):
        m = SET_RE.match(line)
        if m and m.group(2) == "Directory":
            line = m.group(1) + "Directory = out"
        elif m and m.group(2) == "Summary file":
            line = m.group(1) + "Summary file = "
        out.append(line)
    return "\n".join(out)


def block(path, entries):
    """'subsection A / subsection B / set k = v / end / end' for path [A, B]."""
    lines = []
    for depth, sub in enumerate(path):
        lines.append("  " * depth + "subsection " + sub)
    for name, value in entries:
        lines.append("  " * len(path) + "set %s = %s" % (name, value))
    for depth in reversed(range(len(path))):
        lines.append("  " * depth + "end")
    return "\n".join(lines) + "\n"


def find_set_line(lines, name, subsection=None):
    """Index of the first 'set name = ...' line (inside a top-level
    subsection named subsection, if given)."""
    stack = []
    for i, line in enumerate(lines):
        s = line.strip()
        if s.lower().startswith("subsection "):
            stack.append(s[len("subsection "):].strip())
            continue
        if s.lower() == "end":
            if stack:
                stack.pop()
            continue
        m = SET_RE.match(line)
        if m and m.group(2) == name and (subsection is None or
                                         (stack and stack[0] == subsection)):
            return i
    raise KeyError("no 'set %s' line%s" %
                   (name, " in " + subsection if subsection else ""))


def find_subsection_line(lines, name):
    for i, line in enumerate(lines):
        if line.strip() == "subsection " + name:
            return i
    raise KeyError("no 'subsection %s' line" % name)


def first_top_level_end(lines):
    depth = 0
    for i, line in enumerate(lines):
        s = line.strip()
        if s.startswith("subsection "):
            depth += 1
        elif s == "end":
            depth -= 1
            if depth == 0:
                return i
    raise KeyError("no top-level 'end'")


# Mutations. Each takes (lines, rng) and returns (new text, appendable):
# appendable False means the override block must not be appended (it would
# repair or change the structure the mutation broke).

def m_append(path, entries):
    def mutate(lines, rng):
        return "\n".join(lines).rstrip("\n") + "\n" + block(path, entries), True
    return mutate


def m_replace_value(name, value, subsection=None):
    def mutate(lines, rng):
        lines = list(lines)
        i = find_set_line(lines, name, subsection)
        m = SET_RE.match(lines[i])
        lines[i] = m.group(1) + m.group(2) + m.group(3) + value
        return "\n".join(lines), True
    return mutate


def m_rename(name, new_name, subsection=None):
    def mutate(lines, rng):
        lines = list(lines)
        i = find_set_line(lines, name, subsection)
        m = SET_RE.match(lines[i])
        lines[i] = m.group(1) + new_name + m.group(3) + m.group(4)
        return "\n".join(lines), True
    return mutate


def m_drop_equals(name):
    def mutate(lines, rng):
        lines = list(lines)
        i = find_set_line(lines, name)
        m = SET_RE.match(lines[i])
        lines[i] = m.group(1) + m.group(2) + " " + m.group(4)
        return "\n".join(lines), True
    return mutate


def m_truncate_after_subsection(name):
    def mutate(lines, rng):
        i = find_subsection_line(lines, name)
        return "\n".join(lines[:i + 1]) + "\n", False
    return mutate


def m_extra_end():
    def mutate(lines, rng):
        lines = list(lines)
        i = first_top_level_end(lines)
        lines.insert(i + 1, "end")
        return "\n".join(lines), True
    return mutate


GARBAGE_MARK = "\x00GARBAGE\x00"


def m_garbage_line():
    def mutate(lines, rng):
        lines = list(lines)
        # the middle of the file, between two lines
        lines.insert(len(lines) // 2, GARBAGE_MARK)
        return "\n".join(lines), True
    return mutate


def garbage_bytes(rng, n=48):
    """A line of binary garbage: no newline, carriage return, '#' (comment)
    or backslash (line continuation); starts with a byte >= 0x80 so that it
    is neither blank nor a keyword."""
    excluded = {0x0A, 0x0D, ord("#"), ord("\\")}
    first = bytes([rng.randrange(0x80, 0x100)])
    rest = bytes(b for b in (rng.randrange(0, 256) for _ in range(4 * n))
                 if b not in excluded)[:n - 1]
    return first + rest


# (scene, mutation name, mutation, substring the message should contain;
#  None: the prm file name)
M = "Materials"
T = "Time integration"
G = "Geometry"
B = "Boundary conditions"
O = "Output"

PRM_CASES = [
    # names and syntax
    ("box_3d_drag", "unknown-parameter",
     m_append([M], [("Stiffness", "5000")]), "Stiffness"),
    ("liver_gravity", "unknown-subsection",
     m_append(["Solver settings"], [("Tolerance", "1e-8")]), "Solver settings"),
    ("teran_2d_backward_euler", "misspelled-youngs-modulus",
     m_rename("Young's modulus", "Youngs modulus"), "Youngs modulus"),
    ("jeffrey_block", "misspelled-subdivisions",
     m_rename("Subdivisions", "Subdivision"), "Subdivision"),
    ("jeffrey_timing", "misspelled-time-step",
     m_rename("Time step", "Timestep"), "Timestep"),
    ("cook_membrane", "word-subdivisions",
     m_replace_value("Subdivisions", "twelve"), "Subdivisions"),
    ("stability_map", "word-end-time",
     m_replace_value("End time", "twelve"), "End time"),
    ("anisotropic_muscle", "word-youngs-modulus",
     m_replace_value("Young's modulus", "twelve", M), "Young's modulus"),
    ("benchmark_assembly", "word-repetitions",
     m_replace_value("Repetitions", "twelve"), "Repetitions"),
    ("liver_gravity", "word-gravity",
     m_replace_value("Gravity", "0, twelve, 0"), "Gravity"),

    # non-finite numbers
    ("box_3d_drag", "youngs-modulus-nan",
     m_append([M], [("Young's modulus", "nan")]), "Young's modulus"),
    ("benchmark_muscle_force", "youngs-modulus-inf",
     m_append([M], [("Young's modulus", "inf")]), "Young's modulus"),
    ("quasistatic_1d", "youngs-modulus-minus-inf",
     m_append([M], [("Young's modulus", "-inf")]), "Young's modulus"),
    ("jeffrey_muscle", "youngs-modulus-1e400",
     m_append([M], [("Young's modulus", "1e400")]), "Young's modulus"),
    ("teran_2d_backward_euler", "poissons-ratio-nan",
     m_append([M], [("Poisson's ratio", "nan")]), "Poisson's ratio"),
    ("anisotropic_muscle", "poissons-ratio-inf",
     m_append([M], [("Poisson's ratio", "inf")]), "Poisson's ratio"),
    ("cook_membrane", "poissons-ratio-minus-inf",
     m_append([M], [("Poisson's ratio", "-inf")]), "Poisson's ratio"),
    ("benchmark_assembly", "poissons-ratio-1e400",
     m_append([M], [("Poisson's ratio", "1e400")]), "Poisson's ratio"),
    ("liver_gravity", "density-nan",
     m_append([M], [("Density", "nan")]), "Density"),
    ("jeffrey_block", "density-inf",
     m_append([M], [("Density", "inf")]), "Density"),
    ("inversion_recovery", "density-minus-inf",
     m_append([M], [("Density", "-inf")]), "Density"),
    ("jeffrey_timing", "density-1e400",
     m_append([M], [("Density", "1e400")]), "Density"),
    ("jeffrey_table_e1", "time-step-nan",
     m_append([T], [("Time step", "nan")]), "Time step"),
    ("quasistatic_1d", "time-step-inf",
     m_append([T], [("Time step", "inf")]), "Time step"),
    ("stability_map", "time-step-minus-inf",
     m_append([T], [("Time step", "-inf")]), "Time step"),
    ("box_3d_drag", "time-step-1e400",
     m_append([T], [("Time step", "1e400")]), "Time step"),
    ("cook_membrane", "end-time-nan",
     m_append([T], [("End time", "nan")]), "End time"),
    ("liver_gravity", "end-time-inf",
     m_append([T], [("End time", "inf")]), "End time"),
    ("anisotropic_muscle", "end-time-minus-inf",
     m_append([T], [("End time", "-inf")]), "End time"),
    ("jeffrey_muscle", "end-time-1e400",
     m_append([T], [("End time", "1e400")]), "End time"),
    ("inversion_recovery", "gravity-nan",
     m_append([B], [("Gravity", "nan, 0, 0")]), "Gravity"),
    ("teran_2d_backward_euler", "gravity-inf",
     m_append([B], [("Gravity", "0, inf, 0")]), "Gravity"),
    ("jeffrey_table_e1", "gravity-minus-inf",
     m_append([B], [("Gravity", "0, 0, -inf")]), "Gravity"),
    ("quasistatic_1d", "gravity-1e400",
     m_append([B], [("Gravity", "1e400, 0, 0")]), "Gravity"),
    ("box_3d_drag", "upper-corner-nan",
     m_append([G], [("Upper corner", "4, nan, 1")]), "Upper corner"),
    ("jeffrey_block", "lower-corner-inf",
     m_append([G], [("Lower corner", "0, inf, 0")]), "Lower corner"),
    ("poisson_1d", "lower-corner-minus-inf",
     m_append([G], [("Lower corner", "-inf")]), "Lower corner"),
    ("cook_membrane", "corners-1e400",
     m_append([G], [("Corners", "0, 0; 48, 1e400; 0, 44; 48, 60")]),
     "Corners"),

    # out-of-range values
    ("jeffrey_timing", "poissons-ratio-0.5",
     m_append([M], [("Poisson's ratio", "0.5")]), "Poisson's ratio"),
    ("liver_gravity", "poissons-ratio-minus-1",
     m_append([M], [("Poisson's ratio", "-1")]), "Poisson's ratio"),
    ("inversion_recovery", "youngs-modulus-minus-1",
     m_append([M], [("Young's modulus", "-1")]), "Young's modulus"),
    ("jeffrey_table_e1", "youngs-modulus-0",
     m_append([M], [("Young's modulus", "0")]), "Young's modulus"),
    ("teran_2d_backward_euler", "density-minus-1",
     m_append([M], [("Density", "-1")]), "Density"),
    ("jeffrey_block", "time-step-0",
     m_append([T], [("Time step", "0")]), "Time step"),
    ("anisotropic_muscle", "time-step-minus-0.1",
     m_append([T], [("Time step", "-0.1")]), "Time step"),
    ("box_3d_drag", "end-time-0",
     m_append([T], [("End time", "0")]), "End time"),
    ("stability_map", "subdivisions-0",
     m_append([G], [("Subdivisions", "0, 4, 4")]), "Subdivisions"),
    ("poisson_1d", "subdivisions-minus-3",
     m_append([G], [("Subdivisions", "-3")]), "Subdivisions"),
    ("liver_gravity", "global-refinements-99",
     m_append([G], [("Global refinements", "99")]), "Global refinements"),
    ("jeffrey_muscle", "dimension-4",
     m_append([], [("Dimension", "4")]), "Dimension"),
    ("quasistatic_1d", "polynomial-degree-0",
     m_append(["Finite element"], [("Polynomial degree", "0")]),
     "Polynomial degree"),
    ("anisotropic_muscle", "fibre-youngs-modulus-minus-1",
     m_append([M, "Transversely isotropic St Venant-Kirchhoff"],
              [("Young's modulus along fibre", "-1")]),
     "Young's modulus along fibre"),
    ("benchmark_muscle_force", "fibre-poissons-ratio-0.5",
     m_append([M, "Transversely isotropic St Venant-Kirchhoff"],
              [("Poisson's ratio along fibre", "0.5")]),
     "Poisson's ratio along fibre"),

    # wrong counts
    ("box_3d_drag", "lower-corner-two-coordinates",
     m_append([G], [("Lower corner", "0, 0")]), "Lower corner"),
    ("liver_gravity", "probe-two-coordinates",
     m_append([O, "Probes"], [("Points", "-3.5, 1.5; 0, 4.5, 1")]),
     "Output/Probes/Points"),
    ("teran_2d_backward_euler", "probe-one-coordinate",
     m_append([O, "Probes"], [("Points", "0, 0; 1")]),
     "Output/Probes/Points"),
    ("jeffrey_timing", "dirichlet-two-expressions-for-xyz",
     m_append([B], [("Dirichlet",
                     "4: xyz: 0; 0 | 5: xyz: 0.002*sin(2*pi*t); 0; 0")]),
     "Dirichlet"),
    ("inversion_recovery", "three-material-ids-two-models",
     m_append([M], [("Material ids", "0, 1, 2"),
                    ("Model", "robust neo-Hookean, neo-Hookean")]),
     "Materials/"),
    ("jeffrey_block", "one-material-id-two-models",
     m_append([M], [("Material ids", "0"),
                    ("Model", "St Venant-Kirchhoff, St Venant-Kirchhoff")]),
     "Materials/"),

    # expressions with syntax errors
    ("inversion_recovery", "initial-displacement-syntax",
     m_append([B], [("Initial displacement", "0; 0; sin(")]),
     "Initial displacement"),
    ("quasistatic_1d", "dirichlet-syntax",
     m_replace_value("Dirichlet", "0: x: sin(t"), "Dirichlet"),
    ("poisson_1d", "right-hand-side-syntax",
     m_replace_value("Right hand side", "(1 + x)^(-2"), "Right hand side"),
    ("jeffrey_block", "trajectory-syntax",
     m_replace_value("Trajectory", "0.1*min(t,0.1); 0.1*min(t,; 0"),
     "Trajectory"),
    ("anisotropic_muscle", "fibre-direction-syntax",
     m_replace_value("Fibre direction", "1; 0.3*(y - 0.015)/; 0"),
     "Fibre direction"),
    ("jeffrey_muscle", "boundary-predicate-syntax",
     m_replace_value("Boundary id predicates", "1: z < | 2: z > 0.15"),
     "Boundary id predicates"),

    # further hand-parsed entries (tool, predicates, budgets)
    ("jeffrey_block", "trajectory-two-expressions",
     m_replace_value("Trajectory", "0.1*min(t,0.1); 0.1*min(t,0.1)"),
     "Trajectory"),
    ("jeffrey_block", "trajectory-file-missing",
     m_append(["Tool"], [("Trajectory file", "/nonexistent/fuzz/tool.csv")]),
     "Trajectory file"),
    ("jeffrey_muscle", "grasp-point-nan",
     m_replace_value("Grasp point", "0.015, nan, 0.075"), "Grasp point"),
    ("jeffrey_muscle", "grasp-radius-minus-1",
     m_replace_value("Grasp radius", "-1"), "Grasp radius"),
    ("jeffrey_block", "release-time-equals-grasp-time",
     m_replace_value("Release time", "0"), "Release time"),
    ("jeffrey_muscle", "haptic-rate-0",
     m_append(["Tool"], [("Haptic rate", "0")]), "Haptic rate"),
    ("teran_2d_backward_euler", "initial-velocity-syntax",
     m_append([B], [("Initial velocity", "0; sin(")]), "Initial velocity"),
    ("liver_gravity", "material-predicate-syntax",
     m_append([G], [("Material id predicates", "1: x >")]),
     "Material id predicates"),
    ("anisotropic_muscle", "reaction-boundary-id-300",
     m_replace_value("Boundary ids", "300", "Output"),
     "Boundary ids"),
    ("stability_map", "real-time-budget-0",
     m_append([T], [("Real-time budget", "0")]), "Real-time budget"),

    # contact
    ("liver_pressed", "friction-coefficient-negative",
     m_append(["Contact", "Obstacle 1"], [("Friction coefficient", "-0.3")]),
     "Friction coefficient"),
    ("muscle_palpation", "contact-tool-unknown-obstacle",
     m_append(["Contact tool"], [("Obstacle", "prbe")]),
     "Contact tool/Obstacle"),
    ("muscle_palpation", "contact-tool-live-with-motion",
     m_append(["Contact tool"], [("Live port", "0")]),
     "Contact/Obstacle 1/Motion"),
    ("muscle_palpation", "penalty-factor-0",
     m_append(["Contact"], [("Penalty factor", "0")]), "Penalty factor"),
    ("muscle_palpation", "tangential-penalty-ratio-0",
     m_append(["Contact"], [("Tangential penalty ratio", "0")]),
     "Tangential penalty ratio"),
    ("liver_pressed", "motion-file-missing",
     m_append(["Contact", "Obstacle 2"],
              [("Motion file", "/nonexistent/fuzz/press.csv")]),
     "Motion file"),
    ("muscle_palpation", "surface-file-missing",
     lambda lines, rng: ("\n".join(lines).rstrip("\n") + "\n"
                         + block(["Contact", "Obstacle 2"],
                                 [("Shape", "surface")])
                         + block(["Contact", "Obstacle 2", "surface"],
                                 [("File", "/nonexistent/fuzz/organ.stl")]),
                         True),
     "surface/File"),
    ("muscle_palpation", "contact-with-radau",
     m_append([T], [("Integrator", "Radau IIA")]), "Obstacle 1/Shape"),

    # broken structure
    ("cook_membrane", "truncated-after-subsection-materials",
     m_truncate_after_subsection(M), None),
    ("jeffrey_table_e1", "truncated-after-subsection-time-integration",
     m_truncate_after_subsection(T), None),
    ("benchmark_assembly", "truncated-after-subsection-assembly-benchmark",
     m_truncate_after_subsection("Assembly benchmark"), None),
    ("stability_map", "extra-end", m_extra_end(), None),
    ("benchmark_muscle_force", "extra-end", m_extra_end(), None),
    ("jeffrey_muscle", "binary-garbage-line", m_garbage_line(), None),
    ("jeffrey_timing", "binary-garbage-line", m_garbage_line(), None),
    ("teran_2d_backward_euler", "set-without-equals",
     m_drop_equals("Time step"), None),
    ("liver_gravity", "set-without-equals",
     m_drop_equals("Poisson's ratio"), None),
    ("poisson_1d", "set-without-equals",
     m_drop_equals("Refinement cycles"), None),
]


def prepare_scene(repo, scene):
    """The shipped scene with absolute mesh paths and the output rewritten:
    the common start of every mutation of it."""
    path = os.path.join(repo, "parameters", scene + ".prm")
    with open(path, encoding="utf-8") as f:
        text = f.read()
    text = absolutize_mesh_paths(text, os.path.dirname(path))
    return rewrite_output_lines(text)


def prm_cases(repo, rng):
    cases = []
    for scene, mutation, mutate, should in PRM_CASES:
        name = "prm-%s-%s" % (scene, mutation)
        text, appendable = mutate(prepare_scene(repo, scene).split("\n"), rng)
        if appendable:
            text = text.rstrip("\n") + "\n" + OUTPUT_BLOCK
        data = text.encode("utf-8")
        if GARBAGE_MARK.encode() in data:
            data = data.replace(GARBAGE_MARK.encode(), garbage_bytes(rng))
        prm = scene + ".prm"
        cases.append(Case("prm", name, {prm: data}, prm,
                          should_name=should if should else prm))
    return cases


def prm_controls(repo):
    """Each scene as the cases start from it (absolute mesh paths, output
    into the run's directory), which --validate must accept."""
    cases = []
    for scene in sorted({c[0] for c in PRM_CASES}):
        text = prepare_scene(repo, scene).rstrip("\n") + "\n" + OUTPUT_BLOCK
        prm = scene + ".prm"
        cases.append(Case("control", "control-prm-" + scene,
                          {prm: text.encode("utf-8")}, prm,
                          args=["--validate"]))
    return cases


# ---------------------------------------------------------------------------
# Meshes

def mesh_scene(mesh_path, dimension=3):
    return ("# fuzz case: a small scene reading a mutated mesh\n"
            "set Dimension = %d\n"
            "set Problem   = elasticity\n"
            "subsection Geometry\n"
            "  set Source    = file\n"
            "  set Mesh file = %s\n"
            "end\n"
            "subsection Materials\n"
            "  set Model           = neo-Hookean\n"
            "  set Young's modulus = 1000\n"
            "  set Poisson's ratio = 0.3\n"
            "  set Density         = 1\n"
            "end\n"
            "subsection Time integration\n"
            "  set Integrator = backward Euler\n"
            "  set End time   = 0.01\n"
            "  set Time step  = 0.01\n"
            "end\n" % (dimension, mesh_path)) + OUTPUT_BLOCK


class Msh:
    """data/liver.msh (Gmsh 1.0) split into its parts."""

    def __init__(self, path):
        with open(path, encoding="ascii") as f:
            lines = f.read().split("\n")
        i = lines.index("$NOD")
        j = lines.index("$ENDNOD")
        k = lines.index("$ELM")
        e = lines.index("$ENDELM")
        self.head = lines[:i]
        self.nodes = [l.split() for l in lines[i + 2:j]]
        self.elements = [l.split() for l in lines[k + 2:e]]
        self.tail = lines[e + 1:]
        assert int(lines[i + 1]) == len(self.nodes)
        assert int(lines[k + 1]) == len(self.elements)

    def copy(self):
        other = Msh.__new__(Msh)
        other.head = list(self.head)
        other.nodes = [list(n) for n in self.nodes]
        other.elements = [list(e) for e in self.elements]
        other.tail = list(self.tail)
        return other

    def node_lines(self, count=None):
        n = len(self.nodes) if count is None else count
        return ["$NOD", str(n)] + [" ".join(x) for x in self.nodes] + ["$ENDNOD"]

    def element_lines(self, count=None):
        n = len(self.elements) if count is None else count
        return (["$ELM", str(n)] + [" ".join(x) for x in self.elements]
                + ["$ENDELM"])

    def text(self, node_count=None, element_count=None):
        return "\n".join(self.head + self.node_lines(node_count)
                         + self.element_lines(element_count) + self.tail)


def tet_nodes(element):
    """Positions (in the split line) of a tetrahedron's four node ids."""
    assert element[1] == "4" and element[4] == "4"
    return [5, 6, 7, 8]


def msh_cases(repo, rng):
    base = Msh(os.path.join(repo, "data", "liver.msh"))
    original = "\n".join(base.head + base.node_lines() + base.element_lines()
                         + base.tail)
    cases = []   # (name, mesh text or bytes, scene dimension)

    # truncated in the middle of the node list (mid-line)
    lines = original.split("\n")
    cut = 2 + len(base.nodes) // 2
    text = "\n".join(lines[:cut]) + "\n" + lines[cut][:len(lines[cut]) // 2]
    cases.append(("msh-truncated-in-nodes", text, 3))

    # truncated in the element list (after a complete line)
    k = lines.index("$ELM")
    cases.append(("msh-truncated-in-elements",
                  "\n".join(lines[:k + 2 + len(base.elements) // 2]) + "\n", 3))

    cases.append(("msh-node-count-too-large",
                  base.text(node_count=len(base.nodes) + 9), 3))
    cases.append(("msh-element-count-too-large",
                  base.text(element_count=len(base.elements) + 4), 3))

    m = base.copy()
    e = rng.randrange(len(m.elements))
    m.elements[e][rng.choice(tet_nodes(m.elements[e]))] = "9999"
    cases.append(("msh-missing-node-id", m.text(), 3))

    m = base.copy()
    e = rng.randrange(len(m.elements))
    pos = tet_nodes(m.elements[e])
    m.elements[e][pos[3]] = m.elements[e][pos[0]]
    cases.append(("msh-degenerate-repeated-node", m.text(), 3))

    m = base.copy()
    e = rng.randrange(len(m.elements))
    pos = tet_nodes(m.elements[e])
    m.elements[e][pos[1]], m.elements[e][pos[2]] = \
        m.elements[e][pos[2]], m.elements[e][pos[1]]
    cases.append(("msh-inverted-swapped-nodes", m.text(), 3))

    m = base.copy()
    e = rng.randrange(len(m.elements))
    p = rng.choice(tet_nodes(m.elements[e]))
    original_id = m.elements[e][p]
    coords = next(n[1:] for n in m.nodes if n[0] == original_id)
    new_id = str(max(int(n[0]) for n in m.nodes) + 1)
    m.nodes.append([new_id] + coords)
    m.elements[e][p] = new_id
    cases.append(("msh-duplicate-node", m.text(), 3))

    m = base.copy()
    m.nodes[rng.randrange(len(m.nodes))][1 + rng.randrange(3)] = "nan"
    cases.append(("msh-nan-coordinate", m.text(), 3))

    m = base.copy()
    m.nodes[rng.randrange(len(m.nodes))][1 + rng.randrange(3)] = "1.2.3"
    cases.append(("msh-malformed-number", m.text(), 3))

    m = base.copy()
    ids = rng.sample([n[0] for n in m.nodes], 8)
    new_id = str(max(int(x[0]) for x in m.elements) + 1)
    m.elements.append([new_id, "5", "1", "1", "8"] + ids)
    cases.append(("msh-mixed-hexahedron", m.text(), 3))

    # the same with a well-shaped hexahedron (a unit cube away from the
    # liver, on 8 new nodes in Gmsh's order): only the mixing is wrong
    m = base.copy()
    first = max(int(n[0]) for n in m.nodes) + 1
    cube = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
            (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    for i, (x, y, z) in enumerate(cube):
        m.nodes.append([str(first + i), str(20 + x), str(y), str(z)])
    new_id = str(max(int(x[0]) for x in m.elements) + 1)
    m.elements.append([new_id, "5", "1", "1", "8"]
                      + [str(first + i) for i in range(8)])
    cases.append(("msh-mixed-separate-hexahedron", m.text(), 3))

    cases.append(("msh-wrong-dimension", original, 2))
    cases.append(("msh-empty", b"", 3))
    cases.append(("msh-random-bytes",
                  bytes(rng.randrange(256) for _ in range(4096)), 3))
    return [(name, data, dim, ".msh") for name, data, dim in cases]


class Vtu:
    """parameters/meshes/jeffrey_muscle.vtu split into lines, with the
    ranges of its data arrays located."""

    def __init__(self, path):
        with open(path, encoding="ascii") as f:
            self.lines = f.read().split("\n")
        self.arrays = {}
        start = None
        for i, line in enumerate(self.lines):
            if "<DataArray" in line:
                m = re.search(r'Name="([^"]*)"', line)
                key = m.group(1) if m else "Points"
                start = i
            elif "</DataArray>" in line:
                self.arrays[key] = (start + 1, i)   # data lines [a, b)
        self.n_points = int(re.search(r'NumberOfPoints="(\d+)"',
                                      "\n".join(self.lines)).group(1))
        self.n_cells = int(re.search(r'NumberOfCells="(\d+)"',
                                     "\n".join(self.lines)).group(1))

    def values(self, key):
        a, b = self.arrays[key]
        return " ".join(self.lines[a:b]).split()

    def with_arrays(self, replace, n_points=None, n_cells=None,
                    per_line=None):
        """The file with the data of the arrays in replace ({key: list of
        tokens}) replaced (written per_line[key] tokens per line, default:
        as wide as the original's first line)."""
        per_line = per_line or {}
        out = []
        i = 0
        while i < len(self.lines):
            hit = next((k for k, (a, b) in self.arrays.items() if a == i
                        and k in replace), None)
            if hit is None:
                out.append(self.lines[i])
                i += 1
                continue
            a, b = self.arrays[hit]
            indent = re.match(r"\s*", self.lines[a]).group(0)
            width = per_line.get(hit, len(self.lines[a].split()))
            tokens = replace[hit]
            for j in range(0, len(tokens), width):
                out.append(indent + " ".join(tokens[j:j + width]))
            i = b
        text = "\n".join(out)
        if n_points is not None:
            text = text.replace('NumberOfPoints="%d"' % self.n_points,
                                'NumberOfPoints="%d"' % n_points)
        if n_cells is not None:
            text = text.replace('NumberOfCells="%d"' % self.n_cells,
                                'NumberOfCells="%d"' % n_cells)
        return text


def vtu_cases(repo, rng):
    v = Vtu(os.path.join(repo, "parameters", "meshes", "jeffrey_muscle.vtu"))
    original = "\n".join(v.lines)
    points = v.values("Points")
    conn = v.values("connectivity")
    offsets = v.values("offsets")
    types = v.values("types")
    mats = v.values("MaterialIds")
    assert len(points) == 3 * v.n_points and len(conn) == 4 * v.n_cells
    assert len(offsets) == v.n_cells and set(types) == {"10"}
    cases = []

    # truncated in the middle of the connectivity, mid-line
    a, b = v.arrays["connectivity"]
    cut = (a + b) // 2
    cases.append(("vtu-truncated-in-connectivity",
                  "\n".join(v.lines[:cut]) + "\n"
                  + v.lines[cut][:len(v.lines[cut]) // 2], 3))
    # truncated in the points
    a, b = v.arrays["Points"]
    cut = (a + b) // 2
    cases.append(("vtu-truncated-in-points",
                  "\n".join(v.lines[:cut]) + "\n", 3))

    c = list(conn)
    c[rng.randrange(len(c))] = str(v.n_points)       # one past the last
    cases.append(("vtu-missing-point", v.with_arrays({"connectivity": c}), 3))

    p = list(points)
    used = int(rng.choice(conn))
    p[3 * used + rng.randrange(3)] = "nan"
    cases.append(("vtu-nan-coordinate", v.with_arrays({"Points": p}), 3))

    p = list(points)
    used = int(rng.choice(conn))
    p[3 * used + rng.randrange(3)] = "1.2.3"
    cases.append(("vtu-malformed-number", v.with_arrays({"Points": p}), 3))

    c = list(conn)
    cell = rng.randrange(v.n_cells)
    c[4 * cell + 3] = c[4 * cell]
    cases.append(("vtu-degenerate-repeated-node",
                  v.with_arrays({"connectivity": c}), 3))

    p = list(points)
    c = list(conn)
    cell = rng.randrange(v.n_cells)
    k = 4 * cell + rng.randrange(4)
    old = int(c[k])
    p += p[3 * old:3 * old + 3]
    c[k] = str(v.n_points)
    cases.append(("vtu-duplicate-point",
                  v.with_arrays({"Points": p, "connectivity": c},
                                n_points=v.n_points + 1), 3))

    o = list(offsets)
    o[-1] = str(int(o[-1]) + 4)
    cases.append(("vtu-offsets-beyond-connectivity",
                  v.with_arrays({"offsets": o}), 3))

    o = list(offsets)
    o[1] = str(int(o[1]) + 1)       # cell 1 gets 5 vertices, cell 2 three
    cases.append(("vtu-offsets-uneven", v.with_arrays({"offsets": o}), 3))

    closing = ("</Piece>", "</UnstructuredGrid>", "</VTKFile>")
    cases.append(("vtu-closing-tags-removed",
                  "\n".join(l for l in v.lines
                            if l.strip() not in closing) + "\n", 3))

    cases.append(("vtu-point-count-too-large",
                  original.replace('NumberOfPoints="%d"' % v.n_points,
                                   'NumberOfPoints="%d"' % (v.n_points + 50)),
                  3))
    cases.append(("vtu-cell-count-too-large",
                  original.replace('NumberOfCells="%d"' % v.n_cells,
                                   'NumberOfCells="%d"' % (v.n_cells + 60)),
                  3))

    # a hexahedron (VTK type 12) on 8 existing points among the tetrahedra
    c = list(conn) + [str(x) for x in rng.sample(range(v.n_points), 8)]
    o = list(offsets) + [str(int(offsets[-1]) + 8)]
    t = list(types) + ["12"]
    mt = list(mats) + ["0"]
    cases.append(("vtu-mixed-hexahedron",
                  v.with_arrays({"connectivity": c, "offsets": o,
                                 "types": t, "MaterialIds": mt},
                                n_cells=v.n_cells + 1), 3))

    cases.append(("vtu-wrong-dimension", original, 2))
    cases.append(("vtu-empty", b"", 3))
    cases.append(("vtu-random-bytes",
                  bytes(rng.randrange(256) for _ in range(4096)), 3))
    return [(name, data, dim, ".vtu") for name, data, dim in cases]


def mesh_cases(repo, work, rng):
    cases = []
    for name, data, dim, ext in msh_cases(repo, rng) + vtu_cases(repo, rng):
        if isinstance(data, str):
            data = data.encode("ascii")
        mesh = name + ext
        mesh_path = os.path.join(work, name, mesh)
        repair = name == "msh-inverted-swapped-nodes"
        cases.append(Case("repair" if repair else "mesh", name,
                          {mesh: data,
                           "scene.prm": mesh_scene(mesh_path, dim).encode()},
                          "scene.prm", must_name=[mesh],
                          args=["--validate"] if repair else []))
    return cases


def mesh_controls(repo, work):
    cases = []
    for name, source in (("control-mesh-msh",
                          os.path.join(repo, "data", "liver.msh")),
                         ("control-mesh-vtu",
                          os.path.join(repo, "parameters", "meshes",
                                       "jeffrey_muscle.vtu"))):
        with open(source, "rb") as f:
            data = f.read()
        mesh = name + os.path.splitext(source)[1]
        mesh_path = os.path.join(work, name, mesh)
        cases.append(Case("control", name,
                          {mesh: data,
                           "scene.prm": mesh_scene(mesh_path).encode()},
                          "scene.prm", args=["--validate"]))
    return cases


# ---------------------------------------------------------------------------
# Running

def listing(directory):
    found = []
    for root, dirs, files in os.walk(directory):
        for entry in dirs + files:
            found.append(os.path.relpath(os.path.join(root, entry), directory))
    return sorted(found)


def wait_for_executable(exe):
    deadline = time.time() + EXE_WAIT
    while not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        if time.time() > deadline:
            return False
        time.sleep(5)
    return True


def launch(exe, args, cwd):
    """Starts exe in its own process group; retries while the executable is
    missing or being replaced (a rebuild)."""
    deadline = time.time() + EXE_WAIT
    while True:
        if not wait_for_executable(exe):
            raise OSError("executable %s missing for %d s" % (exe, EXE_WAIT))
        try:
            return subprocess.Popen([exe] + args, cwd=cwd,
                                    stdin=subprocess.DEVNULL,
                                    stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE,
                                    start_new_session=True)
        except OSError:
            if time.time() > deadline:
                raise
            time.sleep(5)


def run(exe, args, cwd):
    """(exit status or None on timeout, stdout, stderr, seconds)."""
    start = time.time()
    process = launch(exe, args, cwd)
    try:
        out, err = process.communicate(timeout=TIMEOUT)
        status = process.returncode
    except subprocess.TimeoutExpired:
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        out, err = process.communicate()
        status = None
    return status, out, err, time.time() - start


def shorten(data, limit=400):
    text = data.decode("utf-8", errors="replace")
    text = text.replace("\n", "\\n")
    return text if len(text) <= limit else text[:limit] + "..."


def describe_status(status):
    if status is None:
        return "killed after %d s" % TIMEOUT
    if status < 0:
        try:
            return "signal %s" % signal.Signals(-status).name
        except ValueError:
            return "signal %d" % -status
    return str(status)


def check(exe, work, case, notes):
    """Writes the case's files, runs it, returns a list of problems."""
    directory = os.path.join(work, case.name)
    cwd = os.path.join(directory, "cwd")
    os.makedirs(cwd)
    for name, data in case.files.items():
        with open(os.path.join(directory, name), "wb") as f:
            f.write(data)
    before = listing(directory)
    status, out, err, seconds = run(
        exe, case.args + [os.path.join(directory, case.prm)], cwd)

    problems = []
    # 'repair': input that is safe to repair, run with --validate: exit 0,
    # and the repair must be said on the screen.
    expected = 0 if case.kind in ("control", "repair") else 2
    if status is None:
        problems.append("no exit within %d s (killed)" % TIMEOUT)
    elif status != expected:
        problems.append("exit status %s, expected %d"
                        % (describe_status(status), expected))
    left = listing(cwd)
    if left:
        problems.append("left behind in the working directory: "
                        + ", ".join(left[:8]) + (" ..." if len(left) > 8 else ""))
    appeared = sorted(set(listing(directory)) - set(before) - {"cwd"}
                      - {os.path.join("cwd", x) for x in left})
    if appeared:
        problems.append("written beside the input: " + ", ".join(appeared[:8]))
    # kept for inspection (after the listings above)
    with open(os.path.join(directory, "stderr.txt"), "wb") as f:
        f.write(err)
    if case.kind == "repair" and b"reoriented" not in out:
        problems.append("the repair is not reported on the screen")
    if case.kind not in ("control", "repair"):
        text = err.decode("utf-8", errors="replace")
        body = text[:-1] if text.endswith("\n") else text
        if not body.strip():
            problems.append("stderr is empty")
        elif "\n" in body:
            problems.append("stderr has %d lines" % (body.count("\n") + 1))
        elif not body.startswith(ERROR_PREFIX):
            problems.append("stderr does not start with '%s'" % ERROR_PREFIX)
        for name in case.must_name:
            if name not in text:
                problems.append("stderr does not name '%s'" % name)
        if (not problems and case.should_name
                and case.should_name not in text):
            notes.append("%s: the message does not name '%s': %s"
                         % (case.name, case.should_name, shorten(err)))
    return problems, status, err, seconds


def main(argv):
    if len(argv) != 4:
        sys.stderr.write("usage: %s TISSUEFEM_EXE REPO_ROOT WORK_DIR\n"
                         % argv[0])
        return 2
    exe = os.path.abspath(argv[1])
    repo = os.path.abspath(argv[2])
    work = os.path.abspath(argv[3])
    # WORK_DIR is deleted: refuse anything that holds the repository or
    # the executable, or a top-level directory
    for precious in (repo, os.path.dirname(exe)):
        if precious == work or precious.startswith(work + os.sep):
            sys.stderr.write("refusing to delete WORK_DIR %s: it holds %s\n"
                             % (work, precious))
            return 2
    if work.count(os.sep) < 2:
        sys.stderr.write("refusing to delete WORK_DIR %s\n" % work)
        return 2
    if os.path.exists(work):
        shutil.rmtree(work)
    os.makedirs(work)

    rng = random.Random(SEED)
    cases = prm_cases(repo, rng) + mesh_cases(repo, work, rng)
    controls = prm_controls(repo) + mesh_controls(repo, work)
    names = [c.name for c in cases + controls]
    assert len(names) == len(set(names)), "duplicate case names"

    failures = []
    notes = []
    for case in controls + cases:
        problems, status, err, seconds = check(exe, work, case, notes)
        if problems:
            failures.append(case.name)
            print("FAIL %s: %s (exit %s, stderr: %s)"
                  % (case.name, "; ".join(problems), describe_status(status),
                     shorten(err)), flush=True)
        else:
            print("ok   %s" % case.name, flush=True)

    for note in notes:
        print("note: " + note)
    n_prm = sum(c.kind == "prm" for c in cases)
    n_mesh = sum(c.kind == "mesh" for c in cases)
    n_failed_cases = sum(name in failures for name in (c.name for c in cases))
    n_failed_controls = len(failures) - n_failed_cases
    print("%d cases (%d prm, %d mesh): %d ok, %d failed; %d controls, "
          "%d failed"
          % (len(cases), n_prm, n_mesh, len(cases) - n_failed_cases,
             n_failed_cases, len(controls), n_failed_controls))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
