"""Closed-loop choice (sim/choice.py): first choice and validated choice both kept, never swapped."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from sim.choice import choose, summarize_choices


def _row(obj, gt, rank, ok, seed=0, reason=None):
    return {"object_name": obj, "grasp_type": gt, "rank": rank, "seed": seed, "success": ok,
            "outcome": "success" if ok else "failure", "reason": reason or ("held" if ok else "turned 20 deg")}


def test_validated_choice_is_the_best_ranked_candidate_that_holds():
    rows = [_row("remote", "thumb_4_finger", 0, False, reason="turned 25.8 deg"),
            _row("remote", "medium_wrap", 1, True), _row("remote", "thumb_3_finger", 2, True),
            _row("cup", "heavy_wrap_large_diameter", 0, True), _row("cup", "medium_wrap", 1, True)]
    remote, cup = choose(rows)
    assert (remote.first, remote.first_holds, remote.validated, remote.validated_rank) == (
        "thumb_4_finger", False, "medium_wrap", 1)
    assert remote.differs and remote.first_reason == "turned 25.8 deg"
    assert (cup.first, cup.validated, cup.differs) == ("heavy_wrap_large_diameter", "heavy_wrap_large_diameter", False)
    s = summarize_choices([remote, cup])
    assert (s.objects, s.first_holds, s.validated, s.differs) == (2, 1, 2, 1)
    assert "another candidate for 1, and no candidate holds for 0" in s.describe()


def test_no_candidate_holds_keeps_every_reason_and_counts_as_differing():
    rows = [_row("ball", "power_sphere", 0, False, reason="hand starts inside"),
            _row("ball", "precision_sphere", 1, False, reason="not lifted")]
    (c,) = choose(rows)
    assert c.validated is None and c.validated_rank is None and c.differs
    assert c.reasons == (("power_sphere", "hand starts inside"), ("precision_sphere", "not lifted"))
    # said apart in the summary line: nothing held is not "another grasp held" (grasp validate --top 1)
    line = summarize_choices([c]).describe()
    assert "another candidate for 0, and no candidate holds for 1" in line


def test_a_candidate_holds_only_if_every_seed_held_and_errors_never_hold():
    rows = [_row("box", "thumb_2_finger", 0, True, seed=0), _row("box", "thumb_2_finger", 0, False, seed=1),
            {**_row("box", "medium_wrap", 1, True), "outcome": "error"}, _row("box", "tripod", 2, True)]
    (c,) = choose(rows)
    assert not c.first_holds and c.validated == "tripod" and c.validated_rank == 2


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.sampled_from("abc"), st.integers(0, 4), st.booleans()), min_size=1, max_size=20))
def test_choice_summary_is_consistent_on_any_rows(spec):
    rows = [_row(o, f"type{r}", r, ok) for o, r, ok in spec]
    choices = choose(rows)
    s = summarize_choices(choices)
    assert s.objects == len({o for o, _, _ in spec})
    assert s.first_holds <= s.validated <= s.objects
    assert s.validated - s.first_holds <= s.differs <= s.objects
    best_rank = {o: min(r for o2, r, _ in spec if o2 == o) for o, _, _ in spec}
    for c in choices:
        assert c.first == f"type{best_rank[c.object_name]}"  # the planner's rank stays visible
        if c.validated is not None:
            assert c.validated_rank >= best_rank[c.object_name]
            assert (c.validated_rank == best_rank[c.object_name]) == (not c.differs)
