#!/usr/bin/env python3
# Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
"""The GPU rules that llvmpipe cannot check, checked on the sources (Documentation/design.md,
"GPU rules: for whoever writes a shader or a pass next"). Mesa runs clears and draws in order and keeps NaN semantics,
so a missing texture barrier or a NaN test that fast math folds away passes every image test
here and fails on NVIDIA. This test reads the sources instead:

1. Clears. Every clear in Rendering/ goes through RenderUtilities::ClearForReadBack
   (clear, then texture barrier), or says on the lines above why its target needs no barrier
   ("No barrier needed: ..."). ClearForReadBack's clear is followed by TextureBarrier(), the
   only place that issues the barrier.
2. Draws that read back their target. vtkMultiVolumeRayCastMapper's DrawFragment, the one pass
   whose program reads the textures it draws into (prior opacity, surface progress, reduction
   state), issues TextureBarrier() after its draw whenever it reads back (key.Barrier,
   key.Reduce, key.Surfaces).
3. GLSL: no isnan/isinf, no `x != x`, no negated comparison `!(a <= b)` or `not(lessThan(..))`
   (the NaN tests fast math removes), no variable declared without a value, no
   implicit-derivative lookup (texture(), dFdx, dFdy, fwidth) outside vertex shaders: Strata's
   fragment code runs in ray loops, non-uniform flow.
4. The suite's wiring of GL debug output: every C++ test runs with STRATA_GL_DEBUG=1 and fails
   on "Strata GL debug:" (read from ctest's own listing of the build tree).
5. Compute dispatches (the compute stage, strata::ComputeStage). Every glDispatchCompute (but
   the one inside ComputeStage::Dispatch) and every call of ComputeStage::Dispatch is followed, within the next lines of its function, by
   a glMemoryBarrier or by ComputeStaging::Resolve, whose first GL command is the barrier
   before its texture reads of what the dispatch stored.

Each rule is first run on a known-bad fixture (the code as it was before the H200 findings),
which it must flag: a rule that flags nothing there is broken, and the test fails.
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys

CLEAR = re.compile(r"\b(?:vtkgl|gl)Clear(?:Buffer\w*|Tex(?:Sub)?Image|NamedFramebuffer\w*)?\s*\(")
BARRIER_CALL = re.compile(r"\bglTextureBarrier(?:NV)?\s*\(")
EXEMPT = "No barrier needed:"


def strip_comments(code):
    """C/C++/GLSL comments removed (string literals kept: GLSL lives in them)."""
    out, i, n = [], 0, len(code)
    while i < n:
        if code.startswith("//", i):
            j = code.find("\n", i)
            i = n if j < 0 else j
        elif code.startswith("/*", i):
            j = code.find("*/", i + 2)
            i = n if j < 0 else j + 2
        elif code[i] == '"':
            j = i + 1
            while j < n and code[j] != '"':
                j += 2 if code[j] == "\\" else 1
            out.append(code[i : j + 1])
            i = j + 1
        else:
            out.append(code[i])
            i += 1
    return "".join(out)


def function_body(code, qualified_name):
    """The text between the braces of the definition of `qualified_name`, or None."""
    m = re.search(re.escape(qualified_name) + r"\s*\([^;{]*\)\s*(?:const\s*)?\{", code)
    if not m:
        return None
    depth, i = 1, m.end()
    while depth and i < len(code):
        depth += {"{": 1, "}": -1}.get(code[i], 0)
        i += 1
    return code[m.end() : i - 1]


def function_lines(code, qualified_name):
    """The line numbers of the body of `qualified_name`'s definition (empty when absent)."""
    body = function_body(code, qualified_name)
    if body is None:
        return range(0)
    first = code.count("\n", 0, code.index(body)) + 1
    return range(first, first + body.count("\n") + 1)


def check_clears(name, code):
    """Rule 1 on one C++ source: clears outside ClearForReadBack need the exemption comment."""
    problems = []
    helper = function_lines(code, "RenderUtilities::ClearForReadBack")
    lines = code.split("\n")
    for number, line in enumerate(lines, 1):
        stripped = line.split("//")[0]
        if not CLEAR.search(stripped) or "ClearForReadBack" in stripped or number in helper:
            continue
        above = "\n".join(lines[max(0, number - 4) : number])
        if EXEMPT not in above:
            problems.append(
                f"{name}:{number}: a clear outside ClearForReadBack without '{EXEMPT}' above it: "
                f"{line.strip()}")
    for number, line in enumerate(lines, 1):
        if BARRIER_CALL.search(line.split("//")[0]) and not name.endswith(
                "StrataRenderUtilities.cxx"):
            problems.append(f"{name}:{number}: glTextureBarrier outside "
                            "RenderUtilities::TextureBarrier")
    return problems


def check_helpers(code):
    """Rule 1: ClearForReadBack clears, then calls TextureBarrier(), which issues the barrier."""
    problems = []
    clear = function_body(code, "RenderUtilities::ClearForReadBack")
    barrier = function_body(code, "RenderUtilities::TextureBarrier")
    if clear is None or barrier is None:
        return ["StrataRenderUtilities.cxx: ClearForReadBack or TextureBarrier not found"]
    c = CLEAR.search(clear)
    b = clear.find("TextureBarrier()")
    if not c or b < c.start():
        problems.append("ClearForReadBack: no TextureBarrier() after its clear")
    if not BARRIER_CALL.search(barrier):
        problems.append("TextureBarrier: issues no glTextureBarrier")
    return problems


def check_read_back_draw(code):
    """Rule 2: DrawFragment's draw is followed by TextureBarrier() on every read-back key."""
    body = function_body(code, "vtkMultiVolumeRayCastMapper::vtkInternals::DrawFragment")
    if body is None:
        return ["vtkMultiVolumeRayCastMapper.cxx: DrawFragment not found"]
    draw = body.find(".Draw(")
    if draw < 0:
        return ["DrawFragment: its draw (Geometry.Draw) not found"]
    after = body[draw:]
    m = re.search(r"if\s*\(([^)]*)\)\s*\n?\s*(?:strata::)?RenderUtilities::TextureBarrier\(\)", after)
    if not m:
        return ["DrawFragment: no TextureBarrier() after the draw"]
    missing = [k for k in ("key.Barrier", "key.Reduce", "key.Surfaces") if k not in m.group(1)]
    return [f"DrawFragment: the barrier after the draw skips read-backs of {', '.join(missing)}"
            ] if missing else []


DISPATCH = re.compile(r"\b(?:glDispatchCompute|ComputeStage::Dispatch)\s*\(")
DISPATCH_WINDOW = 12  # lines after a dispatch in which its barrier must come


def check_dispatches(name, code):
    """Rule 5: a dispatch is followed by glMemoryBarrier (or Resolve, which starts with one)."""
    problems = []
    lines = code.split("\n")
    # The helper's own dispatch: its callers are checked instead.
    helper = function_lines(code, "ComputeStage::Dispatch")
    for number, line in enumerate(lines, 1):
        stripped = line.split("//")[0]
        if (not DISPATCH.search(stripped) or number in helper or
                re.search(r"^\s*void\s+ComputeStage::Dispatch", stripped)):
            continue
        after = "\n".join(l.split("//")[0] for l in lines[number - 1 : number + DISPATCH_WINDOW])
        tail = after[DISPATCH.search(after).end():]
        if "glMemoryBarrier(" not in tail and ".Resolve(" not in tail:
            problems.append(f"{name}:{number}: a dispatch without glMemoryBarrier (or Resolve) "
                            f"in the {DISPATCH_WINDOW} lines after it: {line.strip()}")
    return problems


def check_resolve(code):
    """Rule 5: ComputeStaging::Resolve's barrier comes before its draw."""
    body = function_body(code, "ComputeStaging::Resolve")
    if body is None:
        return ["StrataComputeStaging.cxx: ComputeStaging::Resolve not found"]
    barrier, draw = body.find("glMemoryBarrier("), body.find("glDrawArrays(")
    if barrier < 0 or draw < 0 or draw < barrier:
        return ["ComputeStaging::Resolve: no glMemoryBarrier before its draw"]
    return []


GLSL_RULES = [
    (re.compile(r"\bis(?:nan|inf)\s*\("), "isnan/isinf (fast math may fold it to false)"),
    (re.compile(r"(?<![\w.])([A-Za-z_][\w.\[\]]*)\s*!=\s*\1(?![\w.\[])"),
     "x != x (a NaN test fast math folds away)"),
    (re.compile(r"!\s*\((?:[^()]|\([^()]*\))*?(?:<=|>=|==|!=|<|>)"),
     "a negated comparison !(a <= b) (NaN-dependent: write the comparison itself)"),
    (re.compile(r"\bnot\s*\(\s*(?:lessThan|lessThanEqual|greaterThan|greaterThanEqual|equal|"
                r"notEqual)\s*\("), "not(lessThan(..)) (a negated comparison)"),
    (re.compile(r"^\s*(?:const\s+)?(?:float|int|uint|bool|[iub]?vec[234]|mat[234])\s+"
                r"[A-Za-z_][\w@]*\s*(?:\[[^\]]*\])?\s*;"),
     "a variable declared without a value (initialise every GLSL variable)"),
]
DERIVATIVES = (re.compile(r"\b(?:texture|textureProj|textureOffset|dFdx|dFdy|fwidth)\s*\("),
               "an implicit-derivative lookup (texture(), dFdx, fwidth) in fragment code: "
               "use textureLod(.., 0.0) or texelFetch")


def glsl_of_cxx(code):
    """The GLSL a C++ source carries: (line, text) of each string literal, escapes undone."""
    return [(code.count("\n", 0, m.start()) + 1, m.group(1).replace("\\n", "\n"))
            for m in re.finditer(r'"((?:[^"\\]|\\.)*)"', code)]


def check_glsl(name, glsl, vertex, first_line=1):
    problems = []
    code = strip_comments(glsl)
    rules = GLSL_RULES + ([] if vertex else [DERIVATIVES])
    for number, line in enumerate(code.split("\n"), first_line):
        for pattern, why in rules:
            if pattern.search(line):
                problems.append(f"{name}:{number}: {why}: {line.strip()}")
    return problems


def check_cxx_glsl(name, code):
    """Rule 3 on the GLSL in a C++ source's string literals, by the literal's line."""
    problems = []
    for line, text in glsl_of_cxx(code):
        problems += check_glsl(name, text, vertex=False, first_line=line)
    return problems


# Known-bad fixtures: each rule must flag its own.
BAD_CLEAR = """
void DrawFragments(vtkOpenGLState* state)
{
  state->vtkglClearColor(0.0, 0.0, 0.0, 0.0);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
}
"""
BAD_HELPER = """
void RenderUtilities::TextureBarrier()
{
  glTextureBarrier();
}
void RenderUtilities::ClearForReadBack(vtkOpenGLState* state)
{
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
}
"""
BAD_DRAW = """
bool vtkMultiVolumeRayCastMapper::vtkInternals::DrawFragment(Self* self, int f)
{
  this->Geometry.Draw(f);
  if (key.Barrier || key.Reduce)
    RenderUtilities::TextureBarrier();
  return true;
}
"""
BAD_DISPATCH = """
void DispatchFragment(vtkShaderProgram* program, const int rect[4])
{
  strata::ComputeStage::Dispatch(program, rect, origin);
}
"""
BAD_RESOLVE = """
bool ComputeStaging::Resolve(vtkOpenGLRenderWindow* window, const int rect[4])
{
  glDrawArrays(GL_TRIANGLES, 0, 3);
  return true;
}
"""
BAD_GLSL = {
    "x != x": "if (h != h) { continue; }",
    "negated <=": "if (!(abs(h - hHit) <= uZEps)) // NaN (a hole) is not coincident",
    "isnan": "valid = !any(isnan(h));",
    "not(lessThan)": "bvec4 ok = not(lessThan(abs(h), vec4(1.0e30)));",
    "texture()": "float v = texture(uAtlas, p).r;",
    "uninitialised": "vec4 gState;",
}


def self_test():
    """The rules flag the known-bad fixtures; an empty result is a broken rule."""
    failures = []
    if not check_clears("fixture.cxx", BAD_CLEAR):
        failures.append("rule 1 missed a clear without barrier")
    if not check_helpers(BAD_HELPER):
        failures.append("rule 1 missed a ClearForReadBack without barrier")
    if not check_read_back_draw(BAD_DRAW):
        failures.append("rule 2 missed a barrier that skips key.Surfaces")
    if not check_dispatches("fixture.cxx", BAD_DISPATCH):
        failures.append("rule 5 missed a dispatch without barrier")
    if not check_resolve(BAD_RESOLVE):
        failures.append("rule 5 missed a resolve without barrier")
    for what, line in BAD_GLSL.items():
        if not check_glsl("fixture.glsl", line, vertex=False):
            failures.append(f"rule 3 missed {what}")
    return failures


def check_wiring(ctest, build):
    """Rule 4: every C++ test runs with STRATA_GL_DEBUG=1 and fails on the debug line."""
    listing = subprocess.run([ctest, "--show-only=json-v1", "-R", "CoreCxx|IOCxx|RenderingCxx"],
                             cwd=build, capture_output=True, text=True, check=True).stdout
    problems, count = [], 0
    for test in json.loads(listing)["tests"]:
        props = {p["name"]: p["value"] for p in test.get("properties", [])}
        env = props.get("ENVIRONMENT", [])
        count += 1
        if "STRATA_GL_DEBUG=1" not in env:
            problems.append(f"{test['name']}: runs without STRATA_GL_DEBUG=1")
        fail = props.get("FAIL_REGULAR_EXPRESSION", [])
        guard = props.get("PASS_REGULAR_EXPRESSION", [])
        if "Strata GL debug:" not in fail and not any("Strata GL debug:" in g for g in guard):
            problems.append(f"{test['name']}: does not fail on 'Strata GL debug:'")
    return count, problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--source", required=True, help="Strata's source tree")
    parser.add_argument("--build", help="the build tree, for rule 4")
    parser.add_argument("--ctest", default="ctest")
    args = parser.parse_args()

    problems = [f"self-test: {f}" for f in self_test()]
    cxx = sorted(glob.glob(os.path.join(args.source, "Rendering", "*.cxx")))
    clears = dispatches = 0
    for path in cxx:
        code = open(path, encoding="utf-8").read()
        name = os.path.relpath(path, args.source)
        clears += sum(1 for line in code.split("\n") if CLEAR.search(line.split("//")[0]))
        problems += check_clears(name, code)
        if path.endswith("StrataRenderUtilities.cxx"):
            problems += check_helpers(code)
        if path.endswith("vtkMultiVolumeRayCastMapper.cxx"):
            problems += check_read_back_draw(code)
        if path.endswith("StrataComputeStaging.cxx"):
            problems += check_resolve(code)
        found = sum(1 for line in code.split("\n") if DISPATCH.search(line.split("//")[0]))
        dispatches += found
        problems += check_dispatches(name, code)
        problems += check_cxx_glsl(name, code)
    shaders = sorted(glob.glob(os.path.join(args.source, "Rendering", "glsl", "*.glsl")))
    for path in shaders:
        name = os.path.relpath(path, args.source)
        problems += check_glsl(name, open(path, encoding="utf-8").read(),
                               vertex=path.endswith("VS.glsl"))
    pack = os.path.join(args.source, "Module", "StrataFeedbackReduction.cxx")
    problems += check_cxx_glsl("Module/StrataFeedbackReduction.cxx GetGLSLPackFunction",
                               function_body(open(pack, encoding="utf-8").read(),
                                             "FeedbackReduction::GetGLSLPackFunction") or "")
    tests = 0
    if args.build:
        tests, wiring = check_wiring(args.ctest, args.build)
        problems += wiring
    for p in problems:
        print("FAILED:", p)
    print(f"gpu rules: {clears} clears and {dispatches} dispatch lines in {len(cxx)} C++ "
          f"sources, {len(shaders)} GLSL templates "
          f"and the GLSL of the C++ sources, {tests} C++ tests' debug wiring; "
          f"{len(BAD_GLSL) + 5} known-bad fixtures flagged: "
          + ("ok" if not problems else f"{len(problems)} problems"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
