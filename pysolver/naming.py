"""Names of a run's outputs: the unique column names of request channels (CSV headers,
DataFrames, ``Result.units``, plot legends) and the ids the Result's accessors take
(``res.request``, ``res.joint``, ``res.motion``, ``res.controller``: an id, an msolve
element or a label)."""
import numbers

#: What each accessor looks up: (its elements' name in messages, their plural, the classes
#: of pysolver objects that are one: msolve's and pysolver.records').
ELEMENTS = {"request": ("Post_Request", "requests", ("Request",)),
            "joint": ("Constraint_Joint", "joints", ("Joint", "Jprim")),
            "motion": ("motion", "motions", ("Motion",)),
            "controller": ("LoadControl", "tasks", ("LoadControl",))}
#: Most elements an error message lists.
LISTED = 20


def column_names(channels, labels):
    """Unique column names of request `channels`, in their order.

    A channel is named by its label, else ``REQ<id>.<k>``. A name only one channel has (and
    that is not ``time``) is kept as it is; a name several channels have is qualified by the
    request, ``x (request 2)``, and by the channel too when one request has it twice,
    ``x (request 2, channel 3)``. A qualified name that some channel's label already spells
    gets `` #2`` (``#3``, ...).

    Parameters
    ----------
    channels : list of (int, int)
        (request id, channel index 0..7) of each column, in column order.
    labels : dict
        (request id, channel index) -> the channel's name, for those that have one.

    Returns
    -------
    list of str
    """
    bare = [labels.get((rid, k)) or f"REQ{rid}.{k + 1}" for rid, k in channels]
    count, in_request = {"time": 2}, {}
    for (rid, _), name in zip(channels, bare):
        count[name] = count.get(name, 0) + 1
        in_request[rid, name] = in_request.get((rid, name), 0) + 1
    names = [name if count[name] == 1 else f"{name} (request {rid})"
             if in_request[rid, name] == 1 else f"{name} (request {rid}, channel {k + 1})"
             for (rid, k), name in zip(channels, bare)]
    taken = set(bare) | {"time"}
    for i, name in enumerate(names):
        if name != bare[i] and name in taken:
            n = 2
            while f"{name} #{n}" in taken:
                n += 1
            names[i] = f"{name} #{n}"
        taken.add(names[i])
    return names


def element_id(kind, key, known, labels):
    """The id of the element of `kind` (a key of :data:`ELEMENTS`) that `key` names.

    Parameters
    ----------
    kind : str
        ``"request"``, ``"joint"``, ``"motion"`` or ``"controller"``.
    key : int, object or str
        An integer id, an object with an integer ``.id`` (an msolve element; one of
        pysolver's of another kind is refused) or a label.
    known : list of int
        The ids the run has, sorted.
    labels : dict
        id -> label of the elements that have one.

    Returns
    -------
    int

    Raises
    ------
    KeyError
        No element of the run has that id or label (the message lists those there are), or
        the label names several.
    TypeError
        `key` is none of these (a float, None, a Part).
    """
    if type(key) is int and key in known:        # the common case, first
        return key
    what, plural, classes = ELEMENTS[kind]

    def there():
        text = ", ".join(f"{i} {labels[i]!r}" if labels.get(i) else str(i)
                         for i in known[:LISTED]) or "none"
        return text + (f", ... ({len(known)} in all)" if len(known) > LISTED else "")

    if isinstance(key, str):
        ids = [i for i in known if labels.get(i) == key]
        if not ids:
            raise KeyError(f"no {what} labelled {key!r} ({plural}: {there()})")
        if len(ids) > 1:
            raise KeyError(f"the label {key!r} names {what} "
                           f"{', '.join(map(str, ids[:-1]))} and {ids[-1]}: pass the id")
        return ids[0]
    usage = (f"res.{kind} takes a {what} id (int), the {' or '.join(classes)} object or its "
             f"label (str)")
    obj = key
    if not isinstance(key, numbers.Integral) and hasattr(key, "id"):
        cls = type(key).__name__
        if type(key).__module__.startswith("pysolver") and cls not in classes:
            raise TypeError(f"{usage}; got a {cls} (id {key.id})")
        key = key.id
    if isinstance(key, bool) or not isinstance(key, numbers.Integral):
        text = repr(obj) if len(repr(obj)) <= 40 else repr(obj)[:37] + "..."
        got = "None" if obj is None else f"{type(obj).__name__} {text}" if obj is key \
            else f"a {type(obj).__name__} whose id is {key!r}"
        raise TypeError(f"{usage}; got {got}")
    if int(key) not in known:
        raise KeyError(f"no {what} {int(key)} ({plural}: {there()})")
    return int(key)
