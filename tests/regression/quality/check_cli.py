#!/usr/bin/python3
"""Drives `mixmesh check` on the meshes beside this script and asserts its exit
status and JSON report; with --independent also runs check_mesh.py on the same file
and asserts that the two verdicts agree.

    check_cli.py MIXMESH CASE WORKDIR [--independent CHECK_MESH]

CASE: valid | inverted | unreadable | missing
"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def run(command):
    result = subprocess.run(command, capture_output=True, text=True, timeout=300)
    print("$ " + " ".join(command) + f"  -> exit {result.returncode}")
    print(result.stdout[-3000:] + result.stderr[-2000:])
    return result


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    mixmesh, case, workdir = sys.argv[1], sys.argv[2], sys.argv[3]
    independent = sys.argv[5] if len(sys.argv) > 5 and sys.argv[4] == "--independent" else None
    os.makedirs(workdir, exist_ok=True)
    report_path = os.path.join(workdir, f"quality_{case}.json")
    if os.path.exists(report_path):
        os.remove(report_path)
    meshes = {"valid": os.path.join(HERE, "four_types.vtu"),
              "inverted": os.path.join(HERE, "inverted_tetrahedron.vtu"),
              "unreadable": os.path.join(workdir, "quality_garbage.vtu"),
              "missing": os.path.join(workdir, "no_such_mesh.vtu")}
    mesh = meshes[case]
    if case == "unreadable":
        with open(mesh, "w") as file:
            file.write("<VTKFile type='UnstructuredGrid'>truncated")
    histograms = os.path.join(workdir, f"quality_{case}.png")
    if os.path.exists(histograms):
        os.remove(histograms)
    command = [mixmesh, "check", mesh, "--json", report_path]
    if case == "valid":
        command += ["--hist", histograms]
    result = run(command)
    expected = {"valid": 0, "inverted": 1, "unreadable": 2, "missing": 2}[case]
    if result.returncode != expected:
        fail(f"exit status {result.returncode}, expected {expected}")
    if case in ("unreadable", "missing"):
        if "mixmesh: error:" not in result.stderr:
            fail("no error line on stderr")
        if os.path.exists(report_path):
            fail("a report was written for an unreadable mesh")
        print("PASS")
        return 0
    with open(report_path) as file:
        report = json.load(file)
    findings = {finding["check"]: finding for finding in report["findings"]}
    counts = report["counts"]
    if [counts[name] for name in ("tetrahedron", "pyramid", "prism", "hexahedron")] != [1, 1, 1, 1]:
        fail(f"cell counts {counts}")
    if case == "valid":
        if not report["valid"] or any(finding["count"] for finding in findings.values()):
            fail("the four-type mesh is reported invalid")
        jacobian = {entry["entity"]: entry for entry in report["quality"] if entry["metric"] == "scaled_jacobian"}
        if abs(jacobian["hexahedron"]["min"] - 1.0) > 1e-12:
            fail("the unit cube's scaled Jacobian is not 1")
        with open(histograms, "rb") as file:
            if file.read(8) != b"\x89PNG\r\n\x1a\n":
                fail("--hist did not write a PNG")
    else:
        inverted = findings["non_positive_volume"]
        if report["valid"] or inverted["count"] != 1 or inverted["examples"][0]["entity"] != "tetrahedron" \
                or inverted["examples"][0]["index"] != 0:
            fail(f"the inverted tetrahedron is not reported: {inverted}")
        if findings["same_orientation"]["count"] != 2:
            fail("the two wrongly wound interior faces are not reported")
    if independent:
        independent_report = os.path.join(workdir, f"quality_{case}_independent.json")
        verdict = run(["/usr/bin/python3", independent, mesh, "--no-foam", "-q", "--json", independent_report])
        if verdict.returncode != expected:
            fail(f"check_mesh.py exit {verdict.returncode}, mixmesh check exit {expected}")
        # The scaled Jacobian minima agree: Verdict's for tets and hexes, the shared
        # corner formula for pyramids and prisms.
        with open(independent_report) as file:
            theirs = json.load(file)["scaled_jacobian"]
        ours = {entry["entity"]: entry["min"] for entry in report["quality"] if entry["metric"] == "scaled_jacobian"}
        names = {"tetra": "tetrahedron", "pyramid": "pyramid", "wedge": "prism", "hexahedron": "hexahedron"}
        for their_name, statistics in theirs.items():
            value = (statistics.get("vtk") or statistics["own"])["min"]
            if abs(value - ours[names[their_name]]) > 1e-9:
                fail(f"scaled Jacobian of {their_name}: check_mesh.py {value}, mixmesh {ours[names[their_name]]}")
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
