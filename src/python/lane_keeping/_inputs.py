"""What the user hands over, as the extension module takes it: configurations as lists of layers,
runtime changes as "T:key=value" texts, logs as files or tables (the C++ side: src/python/bindings)."""

import math
import numbers
import os
from collections.abc import Mapping

# A string that is no existing file is YAML text when it could not be a path to one.
_YAML_MARKS = (":", "\n", "{")


def _plain(value):
    """Plain Python values (dict, list, str, bool, int, float, None) of a nested structure: numpy scalars
    and arrays, tuples and other mappings become their plain forms; anything else is passed on for the
    core to refuse, naming its key."""
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (str, bool, type(None))):
        return value
    if hasattr(value, "tolist") and not isinstance(value, numbers.Number):  # numpy arrays
        return _plain(value.tolist())
    if hasattr(value, "item") and not isinstance(value, (int, float)):  # numpy scalars
        return value.item()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def config_layers(config, overrides=None):
    """The layers of a configuration, overlaid in order on the paper's defaults (as lk_simulate overlays
    --config files, then --set):

    config: None (the defaults), a path (str or os.PathLike) to a YAML file, YAML text, a nested dict of
            the same schema (dotted keys allowed: {"tracker.k_y": 0.15}), or a list or tuple of these.
    overrides: a dict of keys and values ({"tracker.k_y": 0.15}) or a list of "key=value" texts.
    """
    layers = []
    _add_config(layers, config)
    if overrides is None:
        return layers
    if isinstance(overrides, Mapping):
        layers.append(("dict", _plain(overrides), "<overrides>"))
    elif isinstance(overrides, str):
        layers.append(("set", overrides, "<overrides>"))
    else:
        for assignment in overrides:
            if not isinstance(assignment, str):
                raise TypeError(f"overrides: expected a dict or 'key=value' texts, found {assignment!r}")
            layers.append(("set", assignment, "<overrides>"))
    return layers


def _add_config(layers, config):
    if config is None:
        return
    if isinstance(config, (list, tuple)):
        for part in config:
            _add_config(layers, part)
    elif isinstance(config, os.PathLike):
        layers.append(("file", os.fspath(config)))
    elif isinstance(config, str):
        if os.path.isfile(config) or not any(mark in config for mark in _YAML_MARKS):
            layers.append(("file", config))  # a missing file is reported by the core, naming it
        else:
            layers.append(("text", config, "<yaml>"))
    elif isinstance(config, Mapping):
        layers.append(("dict", _plain(config), "<dict>"))
    else:
        raise TypeError("a configuration is a path, YAML text, a dict or a list of them; found "
                        f"{type(config).__name__}")


def _value_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else {math.inf: ".inf", -math.inf: "-.inf"}.get(value, ".nan")
    if hasattr(value, "item") and not isinstance(value, (int, str)):
        return _value_text(value.item())
    return str(value)


def change_texts(changes):
    """Runtime changes as lk_simulate --change takes them: "T:key=value" texts, or (T, key, value) tuples
    (T in seconds of simulated time), or a dict {T: {key: value}}."""
    if changes is None:
        return []
    if isinstance(changes, Mapping):
        return [f"{_value_text(t)}:{key}={_value_text(v)}"
                for t, assignments in changes.items() for key, v in assignments.items()]
    texts = []
    for change in changes:
        if isinstance(change, str):
            texts.append(change)
        elif isinstance(change, (list, tuple)) and len(change) == 3:
            t, key, value = change
            texts.append(f"{_value_text(t)}:{key}={_value_text(value)}")
        else:
            raise TypeError(f"changes: expected 'T:key=value' or (T, key, value), found {change!r}")
    return texts


def log_source(log, name):
    """A log as the diagnosis' C++ side takes it: ("file", path) for a CSV file or a bag, or ("table",
    (source, column names, float64 values rows x columns)) for a pandas DataFrame or a dict of columns."""
    if isinstance(log, (str, os.PathLike)):
        return ("file", os.fspath(log))
    import numpy as np
    if hasattr(log, "columns") and hasattr(log, "to_numpy"):  # a pandas DataFrame
        columns = [str(c) for c in log.columns]
        values = log.to_numpy(dtype=np.float64, na_value=np.nan)
    elif isinstance(log, Mapping):
        columns = [str(c) for c in log]
        values = np.column_stack([np.asarray(v, dtype=np.float64) for v in log.values()]) if log else np.empty((0, 0))
    else:
        raise TypeError(f"{name}: a log is a CSV or bag path, a pandas DataFrame or a dict of columns; "
                        f"found {type(log).__name__}")
    return ("table", (f"DataFrame {name}", columns, np.ascontiguousarray(values, dtype=np.float64)))
