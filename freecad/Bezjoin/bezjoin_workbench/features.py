"""Parametric features: ``Part::FeaturePython`` objects (FreeCAD's ``App::FeaturePython``
with a shape) whose proxy recomputes the result from linked sources.

Each feature stores

* its sources as link properties: ``App::PropertyLinkSubGlobal`` (one object and one
  edge name such as ``("Sketch", "Edge2")``) or ``App::PropertyLinkSubListGlobal``
  (several), so an edge of a sketch stays linked when the sketch changes ("Global":
  the sources may sit inside a Body or ``App::Part`` other than the result's);
* its parameters as typed properties (group "Bezjoin"): setbacks and radii as
  lengths, orders as integers, modes as enumerations, ...;
* read-only report properties where the operation reports something (group
  "Bezjoin report").

Tree placement (:func:`home_container`): a feature is put in the innermost
``App::Part`` holding all its sources; a PartDesign Body accepts PartDesign features
only, so a feature on a Body's sketch goes to the Part holding that Body, or to the
document root, as FreeCAD's own Part workbench tools do. Its shape is stored in that
container's coordinates, so it shows where the sources are.

``execute`` reads the sources in model (global) coordinates
(:func:`operations.model_shape`, as the commands' selection readers do), or, when all
of them come from one object (a sketch), in that object's own coordinates, or when they
sit in the same containers, in those containers' coordinates, placing the result
afterwards: moving a Body or Part then moves the result rigidly instead of
rebuilding it from other coordinates (where the fair G^k search rounds differently). It
calls the plain operation of :mod:`operations`, so changing a parameter, editing or moving a
source and then ``doc.recompute()`` updates the result. When the operation fails the
shape is emptied and the error raised: FreeCAD marks the object invalid and shows the
library's message (``obj.getStatusString()``), no stale shape is left behind, and every
report property is set to NaN: the numbers of the last good result would describe a
shape that is gone.

``ConsumeSources`` (default True for round corner, round wire and merge, which replace
their sources, False for blend and spline): a source object whose every edge the
feature uses (:func:`consumed_sources`: the whole object, or all its edges picked) is
hidden in the GUI when the feature is made, a link changes or the property is set, as
FreeCAD's own fillet hides its base; a sketch of which it uses only some edges stays in
view, with its other edges. Clearing the property shows the sources again. Headless (no
``ViewObject``) it does nothing. Nothing is deleted or moved in the tree.

The proxies keep no state of their own (``dumps``/``loads`` and
``__getstate__``/``__setstate__`` return None), so a saved document reopens with
``bezjoin_workbench.features.<Class>`` and recomputes.

Make features with :func:`make_blend`, :func:`make_round_corner`,
:func:`make_round_wire`, :func:`make_merge`, :func:`make_spline`; a source is an
object (its whole shape; one edge for the two-edge features) or ``(object,
"Edge3")`` / ``(object, ["Edge1", "Edge2"])``.
"""

import contextlib
import math
import re

import FreeCAD
import Part

from . import operations
from .operations import bezjoin

GROUP = "Bezjoin"
REPORT_GROUP = "Bezjoin report"

#: FreeCAD's property status "read-only in the property editor" (``setEditorMode`` 1).
READ_ONLY = 1
#: ... "hidden in the property editor" (``setEditorMode`` 2).
HIDDEN = 2


class FeatureError(RuntimeError):
    """The operation of a feature failed; the message is the reason (the library's)."""


# ---------------------------------------------------------------------------- sources

def _link_value(source):
    """``source`` as a link property value ``(object, [subnames])``."""
    if isinstance(source, (tuple, list)) and len(source) == 2 and \
            hasattr(source[0], "Document"):
        obj, names = source
        names = [names] if isinstance(names, str) else list(names)
        return obj, names
    return source, []


def _link_list_value(sources):
    """``sources`` (one source or a list of them) as a link list value."""
    if not isinstance(sources, (list, tuple)) or (len(sources) == 2 and
                                                  isinstance(sources[1], (str, list, tuple))
                                                  and hasattr(sources[0], "Document")):
        sources = [sources]
    values = []
    for source in sources:
        obj, names = _link_value(source)
        values.append((obj, names or [""]))  # "": the whole object
    return values


def _pairs(value):
    """A link list property value as ``[(object, subname)]`` in order ("" = whole)."""
    pairs = []
    for obj, names in value or []:
        if isinstance(names, str):
            names = [names]
        names = [name for name in names if name]
        if not names:
            pairs.append((obj, ""))
        pairs.extend((obj, name) for name in names)
    return pairs


def _linked_element(obj, name, links, kind):
    """The element ``name`` of ``obj`` in model coordinates; a FeatureError naming the
    link (``links``: "the first edge links", ...) when ``obj`` no longer has it."""
    try:
        return _source_shape(obj, name)
    except (IndexError, ValueError, RuntimeError) as error:
        # FreeCAD's own words for a missing element are "Index out of bound".
        raise FeatureError(
            f"{links} {obj.Label}.{name}, which {obj.Label} no longer has ({error}): "
            f"link another {kind}") from None


def _link_edge(value, what):
    """The edge a ``PropertyLinkSub`` value names, in model coordinates."""
    if not value or value[0] is None:
        raise FeatureError(f"no {what} is linked")
    obj, names = value
    names = [name for name in ([names] if isinstance(names, str) else names) if name]
    if names:
        if len(names) != 1:
            raise FeatureError(f"the {what} links {len(names)} elements, not one edge")
        shape = _linked_element(obj, names[0], f"the {what} links", "edge")
        if shape.ShapeType != "Edge":
            raise FeatureError(f"the {what} ({obj.Label}.{names[0]}) is not an edge")
        return shape
    edges = _source_shape(obj).Edges
    if len(edges) != 1:
        raise FeatureError(f"the {what} ({obj.Label}) has {len(edges)} edges: link one edge "
                           "(object and edge name)")
    return edges[0]


def source_objects(obj):
    """The objects ``obj`` (a bezjoin feature) takes its sources from, without repeats."""
    found = []
    for source, _name in _linked_names(obj):
        if source is not None and source not in found:
            found.append(source)
    return found


def _chain_of_containers(obj):
    """The GeoFeatureGroups (Body, ``App::Part``) holding ``obj``, innermost first."""
    chain = []
    group = obj.getParentGeoFeatureGroup()
    while group is not None:
        chain.append(group)
        group = group.getParentGeoFeatureGroup()
    return chain


def _accepts_features(group):
    """Whether ``group`` can hold a ``Part::FeaturePython``: an ``App::Part`` (or any
    GeoFeatureGroup) can; a PartDesign Body cannot (it holds PartDesign features,
    sketches and datums only: ``Body.addObject`` raises "Body: object is not allowed")."""
    return not group.isDerivedFrom("PartDesign::Body")


def home_container(obj):
    """Where a feature belongs in the tree: the innermost container that holds every
    one of its sources and accepts a ``Part::FeaturePython`` (see
    :func:`_accepts_features`), or ``None`` (the document root).

    A sketch in an ``App::Part`` gives a result in that Part. A sketch in a Body gives
    a result in the Part holding the Body, if any, else at the document root: a Body
    takes PartDesign features only, so FreeCAD's own Part workbench tools (Part
    Fillet, Part Extrude in 0.20) put their result on a Body's sketch outside the
    Body too, and hide the source."""
    sources = source_objects(obj)
    if not sources:
        return None
    chains = [_chain_of_containers(source) for source in sources]
    for group in chains[0]:
        if all(group in chain for chain in chains[1:]) and _accepts_features(group):
            return group
    return None


def containers(obj):
    """The containers (Body, ``App::Part``: GeoFeatureGroups, innermost first, without
    repeats) holding the sources of ``obj`` but not ``obj`` itself: their placements
    move the sources in the model, so the feature depends on them too (property
    ``Containers``). A container holding the feature as well moves the result with
    the sources (the shape is local to it), and a link to it would be a cycle (its
    ``Group`` links the feature)."""
    own = _chain_of_containers(obj)
    found = []
    for source in source_objects(obj):
        for group in _chain_of_containers(source):
            if group not in found and group not in own:
                found.append(group)
    return found


#: The frame a feature is being built in, set by ``_Feature.execute`` around ``build``
#: (FreeCAD recomputes one feature at a time), from :func:`_build_frame`: the sources'
#: shapes are read in it (:func:`_source_shape`) and the result placed from it
#: afterwards (:func:`_placed_shape`). So moving the containers (a Body, an
#: ``App::Part``) that hold all the sources moves the result rigidly instead of
#: rebuilding it from other coordinates: the fair G^k search rounds differently at
#: other coordinates and can stop at a blend 0.03-0.3 mm away.
_FRAME = None


class _Frame:
    """A build frame: one source object's own coordinates (``source`` set: its shape's
    placement left out), or the coordinates of the containers ``chain`` that hold every
    source (``source`` ``None``; ``example`` one of the sources)."""

    def __init__(self, chain, source=None, example=None):
        self.chain = chain
        self.source = source
        self.example = example if example is not None else source

    def holds(self, obj):
        if self.source is not None:
            return obj is self.source
        return obj is not None and _chain_of_containers(obj) == self.chain

    def to_model(self):
        """The placement from this frame to model coordinates."""
        to_model = operations.placement_to_model(self.example)
        return to_model.multiply(self.source.Shape.Placement) if self.source is not None \
            else to_model


def _build_frame(feature):
    """The frame to build ``feature`` in: its one source object's own coordinates, or the
    coordinates of the containers holding all its sources when they share them, or
    ``None`` (model coordinates)."""
    sources = source_objects(feature)
    if not sources:
        return None
    if len(sources) == 1:
        return _Frame(_chain_of_containers(sources[0]), source=sources[0])
    chains = [_chain_of_containers(source) for source in sources]
    if all(chain == chains[0] for chain in chains):
        return _Frame(chains[0], example=sources[0])
    return None


def _source_shape(obj, name=""):
    """``obj``'s shape, or its element ``name``, in the build frame (``_FRAME``) when it
    holds ``obj``, else in model coordinates (:func:`operations.model_shape`)."""
    frame = _FRAME
    if frame is not None and frame.holds(obj):
        shape = obj.Shape.copy()  # in its containers' coordinates
        if frame.source is not None:
            shape.Placement = FreeCAD.Placement()  # in its own
        return shape.getElement(name) if name else shape
    return operations.model_shape(obj, name) if name else operations.model_shape(obj)


def _placed_shape(obj, shape, frame):
    """``shape``, built in ``frame``, in the coordinates of ``obj``'s containers: moved by
    the source's shape placement (a one-object frame), and by the containers'
    placements only where the frame's containers are not ``obj``'s."""
    if _chain_of_containers(obj) == frame.chain:
        placement = frame.source.Shape.Placement if frame.source is not None \
            else FreeCAD.Placement()
    else:
        placement = operations.placement_to_model(obj).inverse().multiply(frame.to_model())
    return _moved(shape, placement)


def _moved(shape, placement):
    """``shape``'s geometry moved by ``placement`` (a copy; ``shape`` itself when the
    placement is the identity): ``transformShape``, because a feature's own
    ``Placement`` replaces a shape's placement on recompute."""
    if placement.isIdentity():
        return shape
    moved = shape.copy()
    moved.transformShape(placement.toMatrix(), True)
    return moved


def _local_shape(obj, shape):
    """``shape`` (built in model coordinates) in the coordinates of ``obj``'s containers,
    so that FreeCAD's display (the containers' placements applied on top) shows it
    where the sources are. The geometry is moved (``transformShape`` with a copy): a
    feature's own ``Placement`` replaces a shape's placement on recompute."""
    return _moved(shape, operations.placement_to_model(obj).inverse())


def _update_containers(obj):
    if not hasattr(obj, "Containers"):
        return
    wanted = containers(obj)
    if list(obj.Containers) != wanted:
        obj.Containers = wanted


def _linked_names(obj):
    """Every element ``obj`` (a bezjoin feature) links, as ``(object, name)`` pairs in
    order; the name is "" for a whole object."""
    pairs = []
    for property_name in getattr(obj.Proxy, "LINKS", ()):
        value = getattr(obj, property_name, None)
        if value:
            # A single link is one (object, names) entry of a link list.
            pairs.extend(_pairs([value] if property_name in obj.Proxy.SINGLE_LINKS else value))
    return pairs


def _uses_every_edge(source, names):
    """Whether the elements ``names`` of ``source`` ("" = the whole object) cover each of
    its edges: named edges, and the edges of named faces and wires. A name ``source``
    no longer has covers nothing."""
    if "" in names:
        return True
    shape = getattr(source, "Shape", None)
    if shape is None or not shape.Edges:
        return False
    used = []
    for name in names:
        try:
            used.extend(shape.getElement(name).Edges)
        except (IndexError, ValueError, RuntimeError, Part.OCCError):
            continue
    return all(any(edge.isSame(other) for other in used) for edge in shape.Edges)


def consumed_sources(obj):
    """The source objects ``obj`` (a bezjoin feature) replaces, to be hidden in the GUI:
    those whose every edge it uses (see :func:`_uses_every_edge`), none when its
    ``ConsumeSources`` is off. Hiding a sketch of which the feature uses two edges out of
    ten would hide the eight others with them (user testing, session 40), so such a
    sketch stays in view."""
    if not getattr(obj, "ConsumeSources", False):
        return []
    pairs = _linked_names(obj)
    return [source for source in source_objects(obj)
            if _uses_every_edge(source, [name for other, name in pairs if other == source])]


def _set_sources_visible(obj, visible):
    """Show every source object in the GUI (``visible``), or hide those ``obj`` consumes
    (:func:`consumed_sources`), leaving the others as they are: another feature may have
    hidden them, or the user (nothing headless)."""
    if not FreeCAD.GuiUp:
        return
    for source in source_objects(obj) if visible else consumed_sources(obj):
        view = getattr(source, "ViewObject", None)
        if view is not None:
            view.Visibility = visible


def _restoring(obj):
    """Whether ``obj`` (or its document) is being read from a file."""
    document = getattr(obj, "Document", None)
    return "Restore" in getattr(obj, "State", ()) or bool(getattr(document, "Restoring", False))


def _clear_report(obj):
    """Set every report property of ``obj`` (group ``REPORT_GROUP``) to NaN, after a
    failed recompute: the numbers of the last good result would describe a shape that
    is gone (user testing, session 40). FreeCAD 0.20's ``App::PropertyFloat`` holds NaN
    and saves and reopens it (``<Float value="nan"/>``); a NaN cannot be read as a
    result, where 0 or -1 could."""
    for name in obj.PropertiesList:
        if obj.getGroupOfProperty(name) == REPORT_GROUP:
            setattr(obj, name, math.nan)


def _length(value):
    return float(getattr(value, "Value", value))


def _order(value):
    """An order property (-1 = the curve's degree) for the operations."""
    return None if value < 0 else int(value)


# ---------------------------------------------------------------------------- proxies

class _Feature:
    """The common part of the proxies: properties, execute frame, persistence."""

    #: Names of the link properties holding the sources.
    LINKS = ()
    #: Those of them that are single links (``PropertyLinkSub``).
    SINGLE_LINKS = ()
    #: True when the feature replaces its sources (their default ``ConsumeSources``).
    CONSUMES = False

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)
        obj.addProperty("App::PropertyBool", "ConsumeSources", GROUP,
                        "Hide the source objects (the result replaces them)")
        obj.ConsumeSources = self.CONSUMES
        # The sources' containers: a moved Body or Part recomputes the feature.
        obj.addProperty("App::PropertyLinkListGlobal", "Containers", GROUP,
                        "The containers of the sources (kept up to date; read only)")
        obj.setEditorMode("Containers", HIDDEN)

    # properties -------------------------------------------------------------
    @staticmethod
    def _add(obj, kind, name, tooltip, value=None, group=GROUP):
        obj.addProperty(kind, name, group, tooltip)
        if value is not None:
            setattr(obj, name, value)

    @classmethod
    def _add_report(cls, obj, name, tooltip):
        cls._add(obj, "App::PropertyFloat", name, tooltip, group=REPORT_GROUP)
        obj.setEditorMode(name, READ_ONLY)

    def add_properties(self, obj):
        raise NotImplementedError

    # recompute --------------------------------------------------------------
    def execute(self, obj):  # noqa: D102 (FreeCAD's name)
        try:
            _update_containers(obj)  # e.g. a source moved into a Body since
            frame = _build_frame(obj)
            global _FRAME
            _FRAME = frame
            try:
                shape = self.build(obj)
            finally:
                _FRAME = None
        except (FeatureError, bezjoin.BezjoinError, bezjoin.UnsupportedGeometryError,
                bezjoin.LibraryNotFoundError, TypeError, ValueError, Part.OCCError) as error:
            obj.Shape = Part.Shape()  # no stale result behind the error
            _clear_report(obj)  # nor a stale report of it
            message = operations.with_articles(f"{obj.Label}: {error}")
            raise FeatureError(message) from None
        except Exception:
            _clear_report(obj)  # an unexpected error: no stale report either
            raise
        obj.Shape = (_local_shape(obj, shape) if frame is None
                     else _placed_shape(obj, shape, frame))

    def build(self, obj):
        """The result's shape from the current sources and parameters."""
        raise NotImplementedError

    def onChanged(self, obj, prop):  # noqa: N802 (FreeCAD's name)
        if _restoring(obj) or not hasattr(obj, "ConsumeSources"):
            return
        if prop in self.LINKS:
            _update_containers(obj)
        if prop == "ConsumeSources":
            _set_sources_visible(obj, not obj.ConsumeSources)
        elif prop in self.LINKS and obj.ConsumeSources:
            _set_sources_visible(obj, False)

    # persistence: nothing of the proxy's own ----------------------------------
    def dumps(self):
        return None

    def loads(self, state):
        return None

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


def _add_two_edges(obj):
    obj.addProperty("App::PropertyLinkSubGlobal", "FirstEdge", GROUP,
                    "The first source edge (object and edge name)")
    obj.addProperty("App::PropertyLinkSubGlobal", "SecondEdge", GROUP,
                    "The second source edge (object and edge name)")


def _two_edges(obj):
    return _link_edge(obj.FirstEdge, "first edge"), _link_edge(obj.SecondEdge, "second edge")


def _add_orders_and_scales(obj):
    _Feature._add(obj, "App::PropertyInteger", "POrder",
                  "Continuity order at the first edge (-1: the edge's degree)", -1)
    _Feature._add(obj, "App::PropertyInteger", "QOrder",
                  "Continuity order at the second edge (-1: the edge's degree)", -1)
    _Feature._add(obj, "App::PropertyBool", "AutoScale",
                  "Choose the shape scales automatically (least bending; never loops)", True)
    _Feature._add(obj, "App::PropertyFloat", "PScale",
                  "Shape scale at the first edge (when AutoScale is off)", 1.0)
    _Feature._add(obj, "App::PropertyFloat", "QScale",
                  "Shape scale at the second edge (when AutoScale is off)", 1.0)


#: The library's names of the options :func:`_orders_and_scales` passes, and the
#: properties they come from.
_ORDER_AND_SCALE_PROPERTIES = dict(p_order="POrder", q_order="QOrder", p_scale="PScale",
                                   q_scale="QScale")

#: The library's argument name at the head of a message ("p_setback: ...",
#: "p_order = 7 is ...").
_ARGUMENT_AT_HEAD = re.compile(r"^(\w+)(?=: | = )")

#: How the library's messages name the two curves of a corner, and the edges they are.
_CURVE_PHRASES = ((" of P ", " of the first edge "), (" of P's ", " of the first edge's "),
                  (" of Q ", " of the second edge "), (" of Q's ", " of the second edge's "))


@contextlib.contextmanager
def _in_feature_terms(properties):
    """Re-raise a library error of the block in the terms of a two-edge feature
    (:func:`_feature_message`)."""
    try:
        yield
    except bezjoin.BezjoinError as error:
        raise bezjoin.BezjoinError(error.status, error.status_name,
                                   _feature_message(error.message, properties)) from None


def _feature_message(message, properties):
    """A library message in the terms of a two-edge feature: the argument names
    (``properties``: library name to property name) as the properties they come from,
    those with an underscore (``p_setback``) wherever they stand, plain words
    (``radius``) only where the message starts with its argument, and the curves P and
    Q as the first and the second edge (user testing, session 39: the status named
    ``q_setback`` for the Setback)."""
    message = _ARGUMENT_AT_HEAD.sub(lambda m: properties.get(m.group(1), m.group(1)),
                                    message)
    for name, prop in properties.items():
        if "_" in name:
            message = re.sub(rf"\b{name}\b", prop, message)
    for phrase, edge in _CURVE_PHRASES:
        message = message.replace(phrase, edge)
    return message


def _orders_and_scales(obj):
    options = dict(p_order=_order(obj.POrder), q_order=_order(obj.QOrder))
    if obj.AutoScale:
        options.update(auto_scale=True)
    else:
        options.update(p_scale=obj.PScale, q_scale=obj.QScale, auto_scale=False)
    return options


class BlendFeature(_Feature):
    """:func:`operations.blend_edges` of two linked edges: the blend edge."""

    LINKS = SINGLE_LINKS = ("FirstEdge", "SecondEdge")

    def add_properties(self, obj):
        _add_two_edges(obj)
        self._add(obj, "App::PropertyFloat", "U0",
                  "Position on the first edge (fraction of its range; 1 = its end)", 1.0)
        self._add(obj, "App::PropertyFloat", "V0",
                  "Position on the second edge (fraction of its range; 0 = its start)", 0.0)
        _add_orders_and_scales(obj)

    def build(self, obj):
        first, second = _two_edges(obj)
        # U0 and V0 are fractions of the edges' ranges, the library's u0 and v0 their
        # parameters: only the orders and scales are named as properties.
        with _in_feature_terms(_ORDER_AND_SCALE_PROPERTIES):
            return operations.blend_edges(first, second, u0=obj.U0, v0=obj.V0,
                                          **_orders_and_scales(obj))


class RoundCornerFeature(_Feature):
    """:func:`operations.round_corner` of two linked edges, by setback or by radius:
    the three-edge rounded path."""

    LINKS = SINGLE_LINKS = ("FirstEdge", "SecondEdge")
    CONSUMES = True

    def add_properties(self, obj):
        _add_two_edges(obj)
        self._add(obj, "App::PropertyEnumeration", "Method",
                  "Setback: arc lengths kept off the corner; Radius: cut where the circular "
                  "fillet of Radius touches the edges", ["Setback", "Radius"])
        self._add(obj, "App::PropertyLength", "Setback",
                  "Setback along the first edge (Method Setback)", 1.0)
        self._add(obj, "App::PropertyLength", "SecondSetback",
                  "Setback along the second edge (Method Setback; 0: the same as Setback)",
                  0.0)
        self._add(obj, "App::PropertyLength", "Radius", "Fillet radius (Method Radius)", 1.0)
        self._add(obj, "App::PropertyInteger", "Order",
                  "Geometric continuity G^k of the blend (Method Radius; 1..6)", 2)
        _add_orders_and_scales(obj)
        self._add(obj, "App::PropertyBool", "ReverseFirst",
                  "Reverse the first edge (crossing edges)", False)
        self._add(obj, "App::PropertyBool", "ReverseSecond",
                  "Reverse the second edge (crossing edges)", False)

    def build(self, obj):
        first, second = _two_edges(obj)
        reverse = dict(reverse_first=obj.ReverseFirst, reverse_second=obj.ReverseSecond)
        properties = dict(_ORDER_AND_SCALE_PROPERTIES, radius="Radius", order="Order",
                          p_setback="Setback",
                          q_setback="SecondSetback" if obj.SecondSetback else "Setback")
        with _in_feature_terms(properties):
            if obj.Method == "Radius":
                return operations.round_corner(first, second, radius=_length(obj.Radius),
                                               order=obj.Order, **reverse)
            second_setback = _length(obj.SecondSetback) or None
            return operations.round_corner(first, second, setback=_length(obj.Setback),
                                           second_setback=second_setback,
                                           **_orders_and_scales(obj), **reverse)


def _linked_path(value, names=None):
    """The edges of the linked path: one whole object (its wire) or linked edges. When
    ``names`` is a list, it receives each path edge's source element, in path order
    ("Sketch.Edge3"), for messages."""
    pairs = _pairs(value)
    if not pairs:
        raise FeatureError("no source wire or edges are linked")
    labelled = []
    if len(pairs) == 1 and not pairs[0][1]:
        source = pairs[0][0]
        shape = _source_shape(source)
        path = operations.path_edges(shape)
        labelled = [(f"{source.Label}.Edge{k + 1}", edge) for k, edge in enumerate(shape.Edges)]
    else:
        for obj, name in pairs:
            shape = _source_shape(obj, name)
            if name:  # an edge, or the edges of a linked face or wire
                labelled.extend((f"{obj.Label}.{name}", edge) for edge in shape.Edges)
            else:
                labelled.extend((f"{obj.Label}.Edge{k + 1}", edge)
                                for k, edge in enumerate(shape.Edges))
        path = operations.path_edges(Part.Compound([edge for _, edge in labelled]))
    if names is not None:
        names.extend(next((label for label, edge in labelled if edge.isSame(p)), "?")
                     for p in path)
    return path


def _with_source_names(message, names):
    """``message`` followed by the source elements its ``corner i`` (between path edges
    ``i`` and ``i + 1``) and ``curves[i]`` (path edge ``i``) are, from ``names``."""
    notes = []
    for kind, index, _ in dict.fromkeys(operations.PATH_INDEX.findall(message)):
        i = int(index)
        if i >= len(names):
            continue
        if kind == "corner ":
            notes.append(f"corner {i} is {names[i]} -> {names[(i + 1) % len(names)]}")
        else:
            notes.append(f"curves[{i}] is {names[i]}")
    return f"{message} ({'; '.join(notes)})" if notes else message


class RoundWireFeature(_Feature):
    """:func:`operations.round_wire` of a linked wire (a sketch, a polyline) or linked
    edges of one path: one wire with every corner rounded, by radius or setback."""

    LINKS = ("Sources",)
    CONSUMES = True

    def add_properties(self, obj):
        obj.addProperty("App::PropertyLinkSubListGlobal", "Sources", GROUP,
                        "The wire (a whole object) or the edges of one path")
        self._add(obj, "App::PropertyEnumeration", "Method",
                  "Radius: each corner cut where the circular fillet of Radius touches its "
                  "edges; Setback: arc length kept off each corner", ["Radius", "Setback"])
        self._add(obj, "App::PropertyLength", "Radius", "Fillet radius (Method Radius)", 1.0)
        self._add(obj, "App::PropertyLength", "Setback", "Setback (Method Setback)", 1.0)
        self._add(obj, "App::PropertyEnumeration", "Continuity",
                  "Continuity of the blends", [f"G{k}" for k in range(1, 7)])
        obj.Continuity = "G2"
        self._add(obj, "App::PropertyEnumeration", "Closed",
                  "Also round the corner from the last edge to the first (auto: when the "
                  "wire closes)", ["auto", "yes", "no"])
        self._add_report(obj, "MaxArcDeviation",
                         "Largest distance of a blend from its corner's arc (Method Radius)")

    def build(self, obj):
        names = []
        edges = _linked_path(obj.Sources, names)
        closed = {"auto": None, "yes": True, "no": False}[obj.Closed]
        try:
            if obj.Method == "Radius":
                order = int(obj.Continuity[1:])
                rounded = operations.round_wire_by_radius(edges, _length(obj.Radius),
                                                          order=order, closed=closed)
                obj.MaxArcDeviation = rounded.max_arc_deviation
                return rounded.shape
            obj.MaxArcDeviation = 0.0
            return operations.round_wire(edges, setback=_length(obj.Setback),
                                         continuity=obj.Continuity, closed=closed)
        except bezjoin.BezjoinError as error:
            raise bezjoin.BezjoinError(error.status, error.status_name,
                                       _with_source_names(error.message, names)) from None


#: The tooltip of ``MergeFeature.MergeMaxDeviation`` (:func:`operations.edge_deviation`).
#: Until session 40 the property held the library's parametric deviation, under the
#: tooltip "Largest deviation of the merged edge from the two edges".
MERGE_MAX_DEVIATION_TOOLTIP = (
    "Largest distance between the merged edge and the two edges, both ways: from each "
    f"of {operations.DEVIATION_SAMPLES} points along the merged edge to the nearest point "
    f"of the two edges, and from {operations.DEVIATION_SAMPLES} points along each edge "
    "to the nearest point of the merged edge")


class MergeFeature(_Feature):
    """:func:`operations.merge_edges` of two linked edges: one edge."""

    LINKS = SINGLE_LINKS = ("FirstEdge", "SecondEdge")
    CONSUMES = True

    def add_properties(self, obj):
        _add_two_edges(obj)
        self._add(obj, "App::PropertyEnumeration", "Metric", "The merge metric",
                  ["discrete", "l2"])
        self._add(obj, "App::PropertyEnumeration", "MuMode", "How the split mu is chosen",
                  ["optimal", "half", "polygon", "given"])
        self._add(obj, "App::PropertyFloat", "Mu", "The split mu (MuMode given; 0 < mu < 1)",
                  0.5)
        self._add(obj, "App::PropertyBool", "FixEnds", "Keep the outer end points", True)
        self._add(obj, "App::PropertyAngle", "MaxAngle",
                  "Largest angle between the edges at the join",
                  operations.MAX_MERGE_ANGLE_DEGREES)
        self._add(obj, "App::PropertyLength", "MaxGap",
                  "Largest gap between the edges' ends that the merge bridges (0: the ends "
                  "must touch, within the wires' tolerance)", 0.0)
        self._add(obj, "App::PropertyBool", "KeepFirst", "Keep the first edge unchanged",
                  False)
        self._add(obj, "App::PropertyBool", "KeepSecond", "Keep the second edge unchanged",
                  False)
        self._add_report(obj, "MergeMu", "The split mu used")
        self._add_report(obj, "MergeMetric", "The metric's value")
        self._add_report(obj, "MergeMaxDeviation", MERGE_MAX_DEVIATION_TOOLTIP)

    def build(self, obj):
        first, second = _two_edges(obj)
        mu = obj.Mu if obj.MuMode == "given" else obj.MuMode
        merged = operations.merge_edges(first, second, metric=obj.Metric, mu=mu,
                                        fix_ends=obj.FixEnds, keep_first=obj.KeepFirst,
                                        keep_second=obj.KeepSecond,
                                        max_angle=_length(obj.MaxAngle),
                                        max_gap=_length(getattr(obj, "MaxGap", 0.0))
                                        or "touching")
        obj.MergeMu = merged.mu
        obj.MergeMetric = merged.metric_value
        obj.MergeMaxDeviation = merged.max_deviation
        return merged.shape

    def onDocumentRestored(self, obj):  # noqa: N802 (FreeCAD's name)
        # A document saved before session 40 holds the library's parametric deviation
        # under the old tooltip: the number is another measure than the tooltip now
        # says, so it is cleared (NaN) and the feature marked for recompute, which
        # stores the geometric one.
        if hasattr(obj, "MergeMaxDeviation") and \
                obj.getDocumentationOfProperty("MergeMaxDeviation") != \
                MERGE_MAX_DEVIATION_TOOLTIP:
            obj.setDocumentationOfProperty("MergeMaxDeviation", MERGE_MAX_DEVIATION_TOOLTIP)
            obj.MergeMaxDeviation = math.nan
            obj.touch()


def _linked_points(value):
    """On-curve points: linked vertices in order, or the ordered vertices of one linked
    wire (a polyline), in model coordinates."""
    pairs = _pairs(value)
    if not pairs:
        raise FeatureError("no source points are linked")
    if len(pairs) == 1 and not pairs[0][1]:
        wires = _source_shape(pairs[0][0]).Wires
        if len(wires) != 1:
            raise FeatureError(f"{pairs[0][0].Label} is not one polyline: link its vertices")
        if wires[0].isClosed():
            # Its ordered vertices do not repeat the first: the closing side would be
            # dropped without a word (user testing, session 39).
            raise FeatureError(
                f"{pairs[0][0].Label} is a closed polyline, and the spline through on-curve "
                "points is open: link its vertices in order instead, the first again at the "
                "end to come back to it")
        return [vertex.Point for vertex in wires[0].OrderedVertexes]
    points = []
    for obj, name in pairs:
        shape = _linked_element(obj, name, "the points link", "vertex")
        points.extend(vertex.Point for vertex in shape.Vertexes)
    return points


class SplineFeature(_Feature):
    """:func:`operations.spline_through_points` of linked vertices (or one polyline)."""

    LINKS = ("Points",)

    def add_properties(self, obj):
        obj.addProperty("App::PropertyLinkSubListGlobal", "Points", GROUP,
                        "The on-curve points (vertices in order) or one polyline")

    def build(self, obj):
        return operations.spline_through_points(_linked_points(obj.Points))


# ---------------------------------------------------------------------------- makers

def _make(document, proxy_class, name, links, parameters):
    obj = document.addObject("Part::FeaturePython", name)
    proxy_class(obj)
    # A Part::FeaturePython without a view provider proxy gets no display
    # modes in FreeCAD 0.20 and is not drawn: 0 selects Part's own view
    # provider (found by freecad/gui-test.sh; headless there is no ViewObject).
    if FreeCAD.GuiUp and obj.ViewObject is not None:
        obj.ViewObject.Proxy = 0
    for property_name, value in links.items():
        setattr(obj, property_name, value)
    container = home_container(obj)
    if container is not None:
        container.addObject(obj)
        _update_containers(obj)  # the new home is no dependency
    for property_name, value in parameters.items():
        setattr(obj, property_name, value)
    if obj.ConsumeSources:
        _set_sources_visible(obj, False)
    return obj


def make_blend(document, first, second, name="Blend", **parameters):
    """A :class:`BlendFeature` from the ``first`` to the ``second`` source edge;
    ``parameters`` set properties (``U0``, ``V0``, ``POrder``, ``AutoScale``, ...)."""
    return _make(document, BlendFeature, name, {"FirstEdge": _link_value(first),
                                                 "SecondEdge": _link_value(second)},
                 parameters)


def make_round_corner(document, first, second, name="RoundedCorner", **parameters):
    """A :class:`RoundCornerFeature` (``Method``, ``Setback``, ``Radius``, ...)."""
    return _make(document, RoundCornerFeature, name, {"FirstEdge": _link_value(first),
                                                       "SecondEdge": _link_value(second)},
                 parameters)


def make_round_wire(document, sources, name="RoundedWire", **parameters):
    """A :class:`RoundWireFeature` of ``sources``: one object (its wire) or edges
    ``[(object, ["Edge1", ...]), ...]`` (``Method``, ``Radius``, ``Setback``,
    ``Continuity``, ``Closed``)."""
    return _make(document, RoundWireFeature, name, {"Sources": _link_list_value(sources)},
                 parameters)


def make_merge(document, first, second, name="Merged", **parameters):
    """A :class:`MergeFeature` (``Metric``, ``MuMode``, ``Mu``, ``FixEnds``, ...)."""
    return _make(document, MergeFeature, name, {"FirstEdge": _link_value(first),
                                                 "SecondEdge": _link_value(second)},
                 parameters)


def make_spline(document, points, name="OnCurveSpline", **parameters):
    """A :class:`SplineFeature` through ``points``: one polyline object or vertices
    ``[(object, ["Vertex1", ...]), ...]``."""
    return _make(document, SplineFeature, name, {"Points": _link_list_value(points)},
                 parameters)
