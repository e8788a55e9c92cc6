"""Where a committed golden JSON document and a recomputed one differ: the walk the golden
scripts' `--quick` modes share (golden_estimators.py, golden_franke.py, golden_subdivision.py).
Each script says when two leaves agree (its tolerance); everything else must be equal: the same
keys, the same list lengths.
"""


def differences(committed, now, close, path=""):
    """The paths where `committed` and `now` differ, each with both values. `close(a, b, path)`
    decides for two leaves (anything not a dict or a list)."""
    if isinstance(committed, dict) and isinstance(now, dict):
        out = [f"{path}: keys {sorted(set(committed) ^ set(now))}"] if set(committed) != set(now) else []
        for k in sorted(set(committed) & set(now)):
            out += differences(committed[k], now[k], close, f"{path}.{k}")
        return out
    if isinstance(committed, list) and isinstance(now, list):
        out = [f"{path}: {len(committed)} items, now {len(now)}"] if len(committed) != len(now) else []
        for i, (a, b) in enumerate(zip(committed, now)):
            out += differences(a, b, close, f"{path}[{i}]")
        return out
    return [] if close(committed, now, path) else [f"{path}: committed {committed!r}, now {now!r}"]
