"""Progress events, cancellation by the callback, and Ctrl-C (with and without a callback)."""

import _thread
import signal
import threading
import time

import pytest

import envelope


def test_events_are_dicts_in_order(cup):
    events = []
    envelope.simplify(*cup, "1%", threads=1, progress=events.append)
    stages = [e["stage"] for e in events if e["kind"] == "stage"]
    assert stages == ["check", "envelopes", "simplify", "verify"]
    simplify = next(e for e in events if e.get("stage") == "simplify")
    assert simplify["vertices"] == len(cup[0])
    removed = [e for e in events if e["kind"] == "removed"]
    assert removed and all(e["removed"] <= e["attempts"] for e in removed)


def test_callback_returning_false_cancels(cup):
    events = []

    def stop_at_envelopes(event):
        events.append(event)
        return not (event["kind"] == "stage" and event["stage"] == "envelopes")

    with pytest.raises(envelope.Cancelled) as err:
        envelope.simplify(*cup, "1%", threads=1, progress=stop_at_envelopes)
    assert str(err.value) == "cancelled"
    # Stopped at the next check: no stage after the one that asked to stop.
    assert events[-1] == {"kind": "stage", "stage": "envelopes"}


def test_callback_returning_true_or_none_continues(sphere):
    answers = iter([True, None] * 1000)
    out = envelope.simplify(*sphere, "2%", threads=1, progress=lambda e: next(answers))
    assert out.is_certified


def test_exception_in_callback_propagates(cup):
    def boom(event):
        raise RuntimeError("boom")

    with pytest.raises(RuntimeError, match="boom"):
        envelope.simplify(*cup, "1%", threads=1, progress=boom)


def test_lod_levels_and_cancel(cup):
    events = []

    def second_level_stops(event):
        events.append(event)
        return not (event["kind"] == "level" and event["index"] == 2)

    with pytest.raises(envelope.Cancelled):
        envelope.lod(*cup, "1/2%,1%", threads=1, progress=second_level_stops)
    levels = [e for e in events if e["kind"] == "level"]
    assert levels == [
        {"kind": "level", "index": 1, "count": 2},
        {"kind": "level", "index": 2, "count": 2},
    ]


@pytest.mark.parametrize("how", ["raise_signal", "interrupt_main"])
def test_ctrl_c_from_the_callback(cup, how):
    calls = []

    def interrupt(event):
        calls.append(event)
        if len(calls) == 2:
            if how == "raise_signal":
                signal.raise_signal(signal.SIGINT)
            else:
                _thread.interrupt_main()

    with pytest.raises(KeyboardInterrupt):
        envelope.simplify(*cup, "1%", threads=1, progress=interrupt)
    # The run stopped at its next check instead of going on to the end.
    assert not any(e.get("stage") == "verify" for e in calls)


def test_ctrl_c_without_a_callback(cup):
    finished = interrupted = False
    timer = threading.Timer(0.05, _thread.interrupt_main)
    start = time.monotonic()
    try:
        timer.start()
        # Long enough for the timer to fire while it runs (every level of the default chain).
        envelope.lod(*cup, envelope.DEFAULTS["lod_epsilons"], threads=1)
        finished = True
        timer.join()
        time.sleep(0.5)  # a late interrupt lands here, inside the try
    except KeyboardInterrupt:
        interrupted = True
    elapsed = time.monotonic() - start
    assert interrupted and not finished, f"not interrupted ({elapsed:.2f} s)"


def test_progress_must_be_callable(sphere):
    with pytest.raises(envelope.InvalidArgumentError) as err:
        envelope.simplify(*sphere, "1%", progress=5)
    assert str(err.value) == "invalid argument: progress must be callable or None, got int"
