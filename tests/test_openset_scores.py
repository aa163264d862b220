"""AUROC and FPR95 of open-set scores (recall.openset_scores), at their boundaries and as properties."""

import pytest
from hypothesis import given
from hypothesis import strategies as st

from kb.errors import RecallError
from recall.openset_scores import auroc, fpr_at_tpr

scores = st.lists(st.floats(min_value=0, max_value=20, allow_nan=False), min_size=1, max_size=30)


def test_perfect_separation_and_reversal():
    assert auroc([2.0, 3.0], [0.1, 0.5]) == 1.0
    assert auroc([0.1, 0.5], [2.0, 3.0]) == 0.0


def test_ties_count_one_half():
    assert auroc([1.0], [1.0]) == 0.5
    assert auroc([1.0, 2.0], [1.0]) == 0.75


def test_fpr95_threshold_is_the_score_that_flags_95_percent():
    unknown = [float(i) for i in range(1, 21)]  # 20 scores: 19 of them (95 %) are >= 2.0
    assert fpr_at_tpr(unknown, [1.99]) == 0.0
    assert fpr_at_tpr(unknown, [2.0]) == 1.0  # at the threshold counts as flagged
    assert fpr_at_tpr(unknown, [1.0, 3.0], tpr=1.0) == 1.0


def test_fpr_needs_a_rate_and_both_sides():
    with pytest.raises(RecallError, match="tpr"):
        fpr_at_tpr([1.0], [0.0], tpr=0.0)
    with pytest.raises(RecallError, match="at least one"):
        auroc([], [1.0])
    with pytest.raises(RecallError, match="NaN"):
        auroc([float("nan")], [1.0])


@given(scores, scores)
def test_auroc_is_a_probability_and_symmetric(pos, neg):
    a = auroc(pos, neg)
    assert 0.0 <= a <= 1.0
    assert a + auroc(neg, pos) == pytest.approx(1.0)


@given(scores, scores)
def test_fpr_is_a_share_and_shifting_known_down_never_raises_it(pos, neg):
    f = fpr_at_tpr(pos, neg)
    assert 0.0 <= f <= 1.0
    assert fpr_at_tpr(pos, [x - 1.0 for x in neg]) <= f
