"""plan_network: what round_edges will make of the picked chains before it makes anything -- the chains, each
corner where they meet with the blend it will get (the report's kinds), or the corner it would refuse. The
task panel shows it as the user picks; here it is checked against the corners round_edges then reports."""
import pytest

import cases
import MeshRound

V = cases.V


def kinds(corners):
    """(vertex, kind) of each corner (the report's rolled corner names the odd round and the rolled one it
    made; the plan names the three chains as picked)."""
    return sorted((tuple(round(c, 6) for c in k["vertex"]), k["kind"]) for k in corners)


@pytest.mark.parametrize("name, expected", [
    ("box_top_corner", {"mitre": 1}),                # two rounds, the vertical edge sharp
    ("box_corner", {"sphere": 1}),                   # three rounds of one convexity
    ("pocket_rim_square", {"mitre": 4}),             # a closed network of four chains
    ("pocket_rim_walls", {"rolled": 4}),             # two convex rim edges and a concave wall edge at each
])
def test_the_plan_names_each_corner_as_round_edges_then_reports_it(name, expected):
    case = cases.case(name)
    mesh = case.mesh("coarse")
    before = mesh.Topology
    plan = MeshRound.plan_network(mesh, case.seeds, case.radius)
    assert mesh.Topology == before and plan.refusal is None
    assert len(plan.chains) == len(case.seeds)
    found = {}
    for k in plan.corners:
        found[k["kind"]] = found.get(k["kind"], 0) + 1
        assert all(0 <= c < len(plan.chains) for c in k["chains"])
        # each chain named at a corner has an end there (the rolled corner's chains: as picked)
        ends = [w.Vertexes[0].Point for w in (plan.chains[c] for c in k["chains"])] + \
               [w.Vertexes[-1].Point for w in (plan.chains[c] for c in k["chains"])]
        assert min((p - k["vertex"]).Length for p in ends) < 1e-4
    assert found == expected
    res = MeshRound.round_edges(mesh, case.seeds, case.radius)
    assert kinds(plan.corners) == kinds(res.report["corners"])


def test_four_rounds_at_a_pyramids_apex_are_planned_as_one_ball():
    case = cases.case("pyramid")
    plan = MeshRound.plan_network(case.mesh("coarse"), case.seeds, case.radius)
    apex = [k for k in plan.corners if len(k["chains"]) == 4]
    assert len(plan.corners) == 5 and all(k["kind"] == "sphere" for k in plan.corners)
    assert len(apex) == 1 and (apex[0]["vertex"] - V(30, 30, 30)).Length < 1e-4
    assert plan.summary() == "5 corner(s): 5 sphere"


def test_a_corner_round_edges_would_refuse_is_planned_as_refused_by_name():
    case = cases.case("box_top_corner")
    mesh = case.mesh("coarse")
    law = [(case.seeds[0], 3.0), (case.seeds[1], 3.3)]  # different radii at a mitre: not blended yet
    plan = MeshRound.plan_network(mesh, case.seeds, law)
    assert plan.refusal and "with radii 3 and 3.3 there" in plan.refusal and "(100, 60, 40)" in plan.refusal
    assert plan.summary().startswith("Corner not blended:")
    with pytest.raises(MeshRound.RoundingError) as refused:
        MeshRound.round_edges(mesh, case.seeds, law)
    assert refused.value.code == "corner_not_blendable" and str(refused.value) == plan.refusal


def test_chains_that_do_not_meet_have_no_corners_and_bad_input_is_refused_as_round_edges_does(box):
    from conftest import BOX_OTHER_SEED, BOX_SEED
    plan = MeshRound.plan_network(box, [BOX_SEED, BOX_OTHER_SEED], 5.0)
    assert len(plan.chains) == 2 and plan.corners == [] and plan.refusal is None and plan.summary() == ""
    with pytest.raises(MeshRound.RoundingError) as bad:
        MeshRound.plan_network(box, [BOX_SEED], -1.0)
    assert bad.value.code == "invalid_input"
    with pytest.raises(MeshRound.RoundingError) as none:
        MeshRound.plan_network(box, [V(50, 30, 20)], 5.0)  # inside the box, far from every edge
    assert none.value.code == "no_sharp_edge"
