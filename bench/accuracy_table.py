"""Print the accuracy figures of the last accuracy run as a markdown table.

    /usr/bin/python3 -m pytest -q -s -p no:cacheprovider tests/python/test_accuracy.py   # writes the file
    /usr/bin/python3 bench/accuracy_table.py [tests/artifacts/accuracy.json]

One row per case and mesh (fine: elements 0.4 r; coarse: 2.5 r; cad: a CAD export tessellation of long
thin triangles).  Deviations are against OCCT's fillet of the CAD solid the mesh was made from, as a
fraction of r, both ways (result -> fillet, fillet -> result); "allowed" is the test's bound: the
tolerance (r/100) plus the input mesh's own chordal error near the chain plus the yardstick's precision.
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT = os.path.join(HERE, "..", "tests", "artifacts", "accuracy.json")
MEASURE = 0.002  # as in tests/python/test_accuracy.py
ORDER = ["fine", "coarse", "cad"]


def topology(row):
    bad = [f"{row[k]} {label}" for k, label in (("nonmanifold_edges", "non-manifold"),
                                                 ("misoriented_edges", "mis-oriented"),
                                                 ("degenerate_facets", "degenerate")) if row[k]]
    if row["boundary_edges_out"] != row["boundary_edges_in"]:
        bad.append(f"{row['boundary_edges_out'] - row['boundary_edges_in']:+d} boundary")
    if row["self_intersections"]:
        bad.append("self-intersecting")
    if not row["orientation_kept"]:
        bad.append("flipped")
    return ", ".join(bad) or "ok"


def line(row):
    if "error" in row:
        message = " ".join(row["error"].split()).replace("|", "/")
        return f"| {row['case']} | {row['mesh']} | refused: {message} |" + " |" * 7
    allowed = row["tolerance"] / row["r"] + row["input_error"] + MEASURE
    worst = max(row["dev_out_to_ref"], row["dev_ref_to_out"])
    mark = "" if worst <= allowed else " **over**"
    far = row["far_facets_lost"] + row["far_facets_added"] + row["far_vertices_lost"]
    return (f"| {row['case']} | {row['mesh']} | {row['facets_in']} -> {row['facets_out']} "
            f"| {row['dev_out_to_ref']:.4f} / {row['dev_ref_to_out']:.4f}{mark} | {allowed:.4f} "
            f"| {topology(row)} | {far} | {row['min_angle_new_deg']:.1f} ({row['min_angle_input_near_deg']:.1f}) "
            f"| {row['max_dihedral_new_deg']:.1f} | {row['seconds']:.3f} |")


def main(path=DEFAULT):
    with open(path) as f:
        rows = json.load(f)
    rows.sort(key=lambda r: (r["case"], ORDER.index(r["mesh"]) if r["mesh"] in ORDER else 9))
    print("| case | mesh | facets in -> out | deviation / r (result -> fillet / fillet -> result) | allowed / r "
          "| topology | far mesh changed | smallest new angle deg (input's near the chain) "
          "| largest turn between new facets deg | s |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for row in rows:
        print(line(row))


if __name__ == "__main__":
    main(*sys.argv[1:])
