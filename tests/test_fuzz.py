"""The deck fuzzer (tests/fuzz.py) as a test: a fast subset by default, more with
``--fuzz-cases N``. Any outcome other than a DeckError, success=False with a message, or success
with finite results fails the test, with the offending decks in the report."""
import json

import fuzz


def test_fuzzed_decks_give_a_deck_error_a_message_or_finite_results(request, tmp_path):
    n = request.config.getoption("--fuzz-cases")
    counts, bad = fuzz.campaign(n, str(tmp_path), seed=20261124)
    report = "\n".join(f"case {i} ({what}): {json.dumps(out)[:800]}\n{raw[:400]!r}"
                       for i, what, out, raw in bad[:5])
    assert not bad, report
    outcomes = {k: v for k, v in counts.items() if not k.startswith("what:")}
    assert sum(counts[k] for k in fuzz.GOOD) == n, outcomes
    # the mutations reach every stage: most decks are refused, some still run
    assert counts["deck_error"] > n // 3 and counts["success"] > n // 10, outcomes
