"""The Round edges task panel: pick seeds on a mesh, see the chains and a live preview, accept.

Picks: a click on the base mesh reaches handle_pick() through a selection observer; it adds a seed (or a
variable-radius point), traces the chain at once and highlights it.  In the "Existing round" pick mode (the
Rounding's Operation "Change radius of existing round"; existing_round.py) a seed is a point on a round:
the round is recognised, its facets highlighted and its radius shown, and the preview is change_radius'.
The radius limit, rule line and corner plan beside the fields are round_edges_checks.py's.  Scripts and the GUI test call the
same add_seed() / add_radius_point() / set_radius() / preview_now() / accept() without a mouse.

The panel never touches the document before OK: chain highlight and preview are Coin overlays, and the
base mesh is only shown ghosted (restored on close).  OK runs FreeCADGui.doCommand lines (so macros record
them) inside one undo transaction: MeshRound.make_rounding for a new feature, property assignments when
editing one (double click on a Rounding).

Preview and OK run the engine on a worker thread while the window stays alive (progress.py).  Esc during
a run cancels it (within about 0.1 s) and the panel says so; Cancel during a run cancels it and closes the
panel.  A cancelled OK undoes its transaction: the document and the undo stack are as they were.  A value
changed during a preview cancels that preview and starts a new one.
"""
import contextlib
import weakref

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from .. import api, inputs, meshconv, progress, reround, shapes
from ..errors import RoundingError
from ..objects.rounding import ROUND
from . import existing_round, overlays
from .round_edges_checks import RadiusChecks
from .round_edges_form import PICK_LAW_POINT, RoundEdgesForm, quantity_value

PREVIEW_DELAY_MS = 150   # debounce: recompute the preview once the user stops typing/picking
# The live preview rounds at a chordal tolerance of at least this fraction of the largest radius (visually
# the same round, and several times faster on big meshes); OK rounds at the tolerance asked for.
PREVIEW_TOLERANCE_FRACTION = 1.0 / 30.0
GHOST_TRANSPARENCY = 70  # the base mesh stays pickable but lets the preview show through
# The panel's starting values.  thickness: the sheet thickness for the rule r >= k.t (0: no rule check; k is
# radius_limits.DEFAULT_K of the tool); neither is stored in the Rounding, they only check the radius.
DEFAULTS = dict(radius=5.0, tolerance=0.0, feature_angle=30.0, reach=3.0, thickness=0.0, tool="die")

_active = None  # weak reference to the open panel


def active_panel():
    """The open RoundEdgesPanel, or None: lets scripts and the GUI test drive it without a mouse."""
    return _active() if _active else None


class RoundEdgesPanel(RadiusChecks):
    """Task panel to create a Rounding of `base`, or to edit `feature` (whose Base is `base`).  operation:
    the new Rounding's (objects.rounding ROUND: seeds next to sharp edges, or CHANGE_RADIUS: seeds on
    existing rounds, the "Existing round" pick mode); an edited feature's own Operation otherwise."""

    def __init__(self, base, feature=None, seeds=(), operation=ROUND):
        self.base, self.feature, self.doc = base, feature, base.Document
        self.vertices, self.triangles = meshconv.mesh_to_arrays(base.Mesh)  # once: every pick traces
        values = dict(DEFAULTS, **_feature_values(feature)) if feature else dict(DEFAULTS, seeds=[], law=[])
        self.seeds = [FreeCAD.Vector(p) for p in values["seeds"]]
        self.law = list(values["law"])
        self.chain_wires, self.result, self.error = [], None, None
        self.strips = []            # "Existing round": the rounds the seeds are on (change_radius' report rows)
        self.limits = []            # max_radius of the picked chains (ChainLimit each), shown beside the radius
        self.plan = None            # api.NetworkPlan of the picked chains when there are several (their corners)
        self._running = None        # the CancelWatch of the run under way (preview or OK), else None
        self._rerun = False         # a value changed during a preview: preview again once it stopped
        self._close_requested = False  # reject() during a run: close once it stopped
        self.cancelled_by = None    # how the last run was cancelled: None, "esc", "button" or "panel"

        self.form = RoundEdgesForm(values["radius"], values["tolerance"], values["feature_angle"],
                                   values["reach"], values["thickness"], values["tool"],
                                   values.get("operation", operation))
        self._radius_expression = _expression_of(feature, "Radius")
        self._timer = QtCore.QTimer()
        self._timer.setSingleShot(True)
        self._timer.setInterval(PREVIEW_DELAY_MS)
        self._timer.timeout.connect(self.update_preview)
        self._connect_form()

        view = FreeCADGui.getDocument(self.doc.Name).ActiveView
        self._marks = overlays.Overlay(view, on_top=True)
        self._preview = overlays.Overlay(view)
        self._saved_view_state = []
        self._enter_view_state()
        self._picker = _PickObserver(self)
        global _active
        _active = weakref.ref(self)

        self.form.show_law(self.law)
        for seed in seeds:
            self.add_seed(seed)
        self._seeds_changed()
        if feature is not None and "Invalid" in feature.State:  # until the preview says more
            self._show_error(f"{feature.Label} failed to recompute: {feature.getStatusString()}")

    # ------------------------------------------------------------------ picking (mouse or script)
    def handle_pick(self, point):
        """What a click on the base mesh does, according to the pick mode."""
        if self.form.pick_mode() == PICK_LAW_POINT:
            return self.add_radius_point(point)
        return self.add_seed(point)

    def add_seed(self, point):
        """Add a seed if a sharp edge is near it: trace and highlight its chain. True if added."""
        candidate = self.seeds + [FreeCAD.Vector(*point)]
        try:
            self._find(candidate)
        except RoundingError as exc:
            self._show_error(f"Seed not added: {exc}")
            return False
        self.seeds = candidate
        self._seeds_changed(retrace=False)
        return True

    def _find(self, seeds):
        """Trace the sharp-edge chains the seeds pick; in "Existing round" mode recognise the rounds they
        are on instead (their rebuilt sharp edges become the chains).  RoundingError if a seed finds none."""
        if self.form.existing_round():
            self.strips, self.chain_wires = existing_round.recognise(self.vertices, self.triangles, seeds,
                                                                     self.feature_angle(), self.form.reach.value())
        else:
            self.strips = []
            self.chain_wires = api.trace_arrays(self.vertices, self.triangles, seeds, self.feature_angle())

    def remove_seeds(self, rows):
        keep = set(range(len(self.seeds))) - set(rows)
        self.seeds = [s for i, s in enumerate(self.seeds) if i in keep]
        self._seeds_changed()

    def add_radius_point(self, point, radius=None):
        """Add a variable-radius control point at the point of the selected chains nearest to `point`
        (radius defaults to the current constant radius). True if added."""
        if not self.chain_wires:
            self._show_error("Radius point not added: select the edge first (pick it as an edge to round); "
                             "radius points lie on its chain.")
            return False
        on_chain = shapes.nearest_on_polylines(point, [shapes.wire_points(w) for w in self.chain_wires])
        radius = radius if radius is not None else quantity_value(self.form.radius)
        self.law.append((*on_chain, float(radius)))
        self.form.show_law(self.law)
        self._refresh_marks()
        self.schedule_preview()
        return True

    def set_radius(self, radius):
        self.form.radius.setProperty("rawValue", float(radius))  # fires valueChanged -> preview

    def overlays(self):
        """The temporary drawing layers (chain marks, preview) this panel put into the 3D view."""
        return self._marks, self._preview

    def feature_angle(self):
        return quantity_value(self.form.feature_angle)

    # ------------------------------------------------------------------ parameters and preview
    def parameters(self):
        """The current inputs as api.round_edges keyword arguments (ValueError: bad table cell)."""
        self.law = self.form.law_rows()
        radius = ([(FreeCAD.Vector(*row[:3]), row[3]) for row in self.law] if self.law
                  else quantity_value(self.form.radius))
        return dict(seeds=list(self.seeds), radius=radius,
                    tolerance=self.form.tolerance.value() or None,
                    feature_angle=self.feature_angle(), reach=self.form.reach.value())

    def _engine(self):
        """What the preview runs: round_edges, or change_radius in "Existing round" mode (same arguments)."""
        return reround.change_radius_arrays if self.form.existing_round() else api.round_arrays

    def schedule_preview(self):
        if self.form.live_preview.isChecked():
            self._timer.start()  # restarts: many quick changes give one computation

    def preview_now(self):
        """Compute the preview at once (tests, or to skip the debounce); returns the RoundingResult."""
        self._timer.stop()
        self.update_preview()
        return self.result

    def preview_parameters(self):
        """parameters() with the preview's (coarser) tolerance; and the tolerance OK will use, in mm."""
        p = self.parameters()
        largest = max(r for _, r in p["radius"]) if isinstance(p["radius"], list) else p["radius"]
        final = p["tolerance"] or inputs.automatic_tolerance(largest)
        p["tolerance"] = max(final, largest * PREVIEW_TOLERANCE_FRACTION)
        return p, final

    def update_preview(self):
        if self._running is not None:  # a value changed meanwhile: stop that preview, then start anew
            self._rerun = True
            progress.cancel_all()
            return
        self.result = None
        self._preview.clear()
        if not self.seeds:
            self.form.show_status(self.form.pick_hint())
            return
        self._show_limit()
        self._plan_corners()  # the radius decides some corners (four faces and one ball)
        self._refresh_marks()
        past = self.radius_past_limit()
        if past:  # refused here, with the reason next to the field
            self._show_error(past)
            return
        watch = None
        try:
            parameters, final_tolerance = self.preview_parameters()
            self.form.show_status("Computing the preview ... (Esc stops it)")
            # No progress indicator: its event filter would eat the keys typed meanwhile.
            with self._cancellable() as watch, progress.busy("Preview", indicator=False) as token:
                self.result = self._engine()(self.vertices, self.triangles, cancel=token, **parameters)
        except (RoundingError, ValueError) as exc:
            self.result = None
            if getattr(exc, "code", None) == "cancelled":
                self._after_cancel((watch and watch.by) or "panel", "Preview cancelled.")
            else:
                self._show_error(str(exc))
            return
        if self._after_run():
            return
        contacts = [shapes.wire_points(w) for w in self.result.contacts]
        self._preview.show(overlays.mesh_node(self.result.vertices, self.result.triangles),
                           overlays.polylines_node(contacts, overlays.CONTACT_COLOR, width=2.0))
        self.error = None
        self.form.show_status(_summary(self.result.report, parameters["tolerance"], final_tolerance))

    # ------------------------------------------------------------------ OK / Cancel
    def accept(self):
        """OK: one undo transaction of recorded commands.  If they fail, or the rounding they make fails
        to recompute, the transaction is undone, the panel stays open and shows why."""
        self._timer.stop()
        if not self.seeds:
            self._show_error("Select at least one sharp edge (click next to it) before OK.")
            return False
        try:
            commands = self._edit_commands() if self.feature else self._create_commands()
        except (RoundingError, ValueError) as exc:
            self._show_error(str(exc))
            return False
        view_state = self._leave_view_state()  # before the commands: make_rounding hides the base itself
        names_before = {o.Name for o in self.doc.Objects}
        self.doc.openTransaction("Edit rounding" if self.feature else "Round edges")
        with self._cancellable() as watch:  # the recompute runs the engine under busy(): Esc reaches us
            try:
                for line in commands + [f"{_doc_expr(self.doc)}.recompute()"]:
                    FreeCADGui.doCommand(line)
                failure = self._recompute_failure(names_before)
            except Exception as exc:  # doCommand reports Python errors as generic exceptions
                failure = f"Could not apply: {exc}"
        if watch.by == "esc" and not failure:
            watch.by = None  # Esc after the engine's last poll: the rounding is made, and kept
        if failure or watch.by:
            self.doc.abortTransaction()
            _apply_view_state(view_state)  # e.g. make_rounding hid the base: show it as it was
            self._enter_view_state()
            if watch.by:
                self._after_cancel(watch.by, "Rounding cancelled: the document is unchanged.")
            else:
                self._show_error(failure)
                self._after_run()
            return False
        self.doc.commitTransaction()
        self._finish()
        return True

    def reject(self):
        if self._running is not None:  # mid-run (e.g. a script): stop the run, close once it stopped
            self._close_requested = True
            self._running.cancel("panel")
            return False
        self._leave_view_state()
        self._finish()
        return True

    def cancel_run(self):
        """What Esc does during a run: stop it, keep the panel open.  True if a run was going."""
        if self._running is None:
            return False
        self._running.cancel("esc")
        return True

    def running(self):
        return self._running is not None

    @contextlib.contextmanager
    def _cancellable(self):
        """The block is a run: Esc and the task dialog's Cancel button cancel it (progress.CancelWatch)."""
        self.cancelled_by = None
        with progress.CancelWatch([_task_cancel_button()]) as watch:
            self._running = watch
            try:
                yield watch
            finally:
                self._running = None

    def _after_cancel(self, by, message):
        """A run stopped on request: close (Cancel), preview again (a value changed), or say so (Esc)."""
        self.cancelled_by = by
        if by == "button":
            self._close_requested = True
        if self._after_run():
            return
        self.form.show_status(message, error=True)

    def _after_run(self):
        """Act on what was asked during the run; True if the panel closed or a new preview follows."""
        if self._close_requested:
            self._close_requested = False
            self._rerun = False
            QtCore.QTimer.singleShot(0, self._close_now)  # out of the call stack that ran the engine
            return True
        if self._rerun:
            self._rerun = False
            self._timer.start()
            return True
        return False

    def _close_now(self):
        if active_panel() is self:
            self.reject()

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def _create_commands(self):
        p = self.parameters()
        return ["import MeshRound",
                f"MeshRound.make_rounding({_doc_expr(self.doc)}.getObject({self.base.Name!r}), "
                f"{_vectors_code(p['seeds'])}, {_radius_code(p['radius'])}, "
                f"tolerance={p['tolerance'] or 0.0!r}, feature_angle={p['feature_angle']!r}, "
                f"reach={p['reach']!r}{_operation_code(self.form.operation())})"]

    def _edit_commands(self):
        p = self.parameters()
        obj = f"{_doc_expr(self.doc)}.getObject({self.feature.Name!r})"
        lines = [f"{obj}.Seeds = {_vectors_code(p['seeds'])}",
                 f"{obj}.RadiusLaw = {_vectors_code([row[:3] for row in self.law])}",
                 f"{obj}.RadiusLawRadii = {[row[3] for row in self.law]!r}",
                 f"{obj}.Tolerance = {p['tolerance'] or 0.0!r}",
                 f"{obj}.FeatureAngle = {p['feature_angle']!r}",
                 f"{obj}.Reach = {p['reach']!r}",
                 f"{obj}.Operation = {self.form.operation()!r}"]
        if not self._radius_expression:
            lines.insert(1, f"{obj}.Radius = {quantity_value(self.form.radius)!r}")
        return lines

    def _recompute_failure(self, names_before):
        """The error of the rounding that OK made or edited, if its recompute failed; else None."""
        if self.feature:
            rounding = self.feature
        else:
            made = [o for o in self.doc.Objects
                    if o.Name not in names_before and o.TypeId == "Mesh::FeaturePython"]
            rounding = made[0] if made else None
        if rounding is None:
            return "Could not apply: no Rounding feature was made"
        if "Invalid" in rounding.State or "Touched" in rounding.State:
            return f"Rounding failed: {rounding.getStatusString() or 'recompute failed'}"
        return None

    def _finish(self):
        """Close the dialog (and edit mode); overlays and observer go away."""
        global _active
        _active = None
        self._timer.stop()
        self._picker.remove()
        self._marks.remove()
        self._preview.remove()
        if self.feature:
            FreeCADGui.getDocument(self.doc.Name).resetEdit()
        else:
            FreeCADGui.Control.closeDialog()

    # ------------------------------------------------------------------ internals
    def _connect_form(self):
        f = self.form
        for box in (f.radius, f.tolerance, f.reach):
            box.valueChanged.connect(lambda *_: self.schedule_preview())
        f.radius.valueChanged.connect(lambda *_: self._show_limit())
        f.thickness.valueChanged.connect(lambda *_: self._show_rules())
        f.tool.currentIndexChanged.connect(lambda *_: self._show_rules())
        f.feature_angle.valueChanged.connect(lambda *_: self._seeds_changed())
        f.reach.valueChanged.connect(lambda *_: self._measure_limits())
        f.law_table.itemChanged.connect(lambda *_: self._law_edited())
        f.live_preview.toggled.connect(lambda on: self.schedule_preview() if on else self._preview.clear())
        f.remove_seed_button.clicked.connect(lambda: self.remove_seeds(f.selected_seed_rows()))
        f.clear_seeds_button.clicked.connect(lambda: self.remove_seeds(range(len(self.seeds))))
        f.remove_law_button.clicked.connect(self._remove_law_rows)
        f.pick_target.currentIndexChanged.connect(lambda *_: self._operation_changed())

    def _operation_changed(self):
        """Sharp edges <-> existing round: the seeds and radius points of the one mean nothing in the other."""
        self.seeds, self.law = [], []
        self.form.show_law(self.law)
        self._seeds_changed()

    def _seeds_changed(self, retrace=True):
        """After seeds or feature angle changed: list, chains, highlight, preview."""
        self.form.show_seeds(self.seeds)
        if retrace:
            self.chain_wires, self.strips = [], []
            if self.seeds:
                try:
                    self._find(self.seeds)
                except RoundingError as exc:
                    self._show_error(str(exc))
        self._measure_limits()
        self._plan_corners()
        self._refresh_marks()
        self.schedule_preview()
        if not self.seeds:
            self.update_preview()  # shows the hint and clears an old preview at once

    def _law_edited(self):
        try:
            self.law = self.form.law_rows()
        except ValueError as exc:
            self._show_error(str(exc))
            return
        self._refresh_marks()
        self.schedule_preview()

    def _remove_law_rows(self):
        rows = set(self.form.selected_law_rows())
        self.law = [row for i, row in enumerate(self.law) if i not in rows]
        self.form.show_law(self.law)
        self._refresh_marks()
        self.schedule_preview()

    def _refresh_marks(self):
        self._update_radius_field()
        chains = [shapes.wire_points(w) for w in self.chain_wires]
        corners = self.corner_marks()
        self.form.show_found(existing_round.found_text(self.strips))
        self._marks.show(existing_round.strips_node(self.vertices, self.triangles, self.strips),
                         overlays.polylines_node(chains, overlays.CHAIN_COLOR, width=5.0),
                         overlays.markers_node([tuple(s) for s in self.seeds], overlays.SEED_COLOR),
                         overlays.markers_node([row[:3] for row in self.law], overlays.LAW_COLOR),
                         *(overlays.markers_node([point], color) for point, color in corners))

    def _show_error(self, message):
        self.error = message
        self.form.show_status(message, error=True)

    def _enter_view_state(self):
        """Ghost the base (pickable, see-through); hide the edited feature so the preview shows."""
        changes = [(self.base.ViewObject, "Visibility", True),
                   (self.base.ViewObject, "Transparency", GHOST_TRANSPARENCY)]
        if self.feature:
            changes.append((self.feature.ViewObject, "Visibility", False))
        self._saved_view_state = [(vobj, name, getattr(vobj, name)) for vobj, name, _ in changes]
        for vobj, name, value in changes:
            setattr(vobj, name, value)

    def _leave_view_state(self):
        """Restore the view properties the panel changed; returns them (for _apply_view_state)."""
        saved, self._saved_view_state = self._saved_view_state, []
        _apply_view_state(saved)
        return saved


class _PickObserver:
    """Selection observer: a click on the base mesh in the 3D view becomes a pick at the clicked point.

    FreeCAD's navigation style decides what a click is (a drag that rotates the view selects nothing).
    A mesh selection has no sub-element, so a 3D click is told from a tree click by its point: the tree
    (and Selection.addSelection without coordinates) report exactly (0, 0, 0).
    """

    def __init__(self, panel):
        self.panel = panel
        FreeCADGui.Selection.addObserver(self)

    def remove(self):
        FreeCADGui.Selection.removeObserver(self)

    def addSelection(self, doc_name, obj_name, sub, point):
        panel = self.panel
        if doc_name != panel.doc.Name or obj_name != panel.base.Name or tuple(point) == (0.0, 0.0, 0.0):
            return
        panel.handle_pick(FreeCAD.Vector(*point))
        # keep the base unselected: the view stays readable and the next click is a new selection
        QtCore.QTimer.singleShot(0, FreeCADGui.Selection.clearSelection)


def _task_cancel_button():
    """The Cancel button of the open task dialog, or None."""
    for box in FreeCADGui.getMainWindow().findChildren(QtGui.QDialogButtonBox):
        button = box.button(QtGui.QDialogButtonBox.Cancel)
        if button is not None and button.isVisible():
            return button
    return None


def _apply_view_state(saved):
    for vobj, name, value in reversed(saved):
        setattr(vobj, name, value)


def _feature_values(feature):
    return dict(seeds=list(feature.Seeds), operation=getattr(feature, "Operation", ROUND),
                law=[(p.x, p.y, p.z, r) for p, r in zip(feature.RadiusLaw, feature.RadiusLawRadii)],
                radius=feature.Radius.Value, tolerance=feature.Tolerance.Value,
                feature_angle=feature.FeatureAngle.Value, reach=feature.Reach)


def _expression_of(obj, name):
    """The expression bound to property `name` of obj, or None."""
    if obj is None:
        return None
    return dict((path.lstrip("."), expr) for path, expr in obj.ExpressionEngine).get(name)


def _summary(report, tolerance, final_tolerance):
    deviation = report.get("max_deviation")
    angle = report.get("min_new_angle_deg")
    text = (f"Preview: {report.get('chains')} chain(s), {report.get('facets_removed')} facets removed, "
            f"{report.get('facets_added')} added; max deviation "
            f"{'-' if deviation is None else f'{deviation:.4f} mm'}, smallest new angle "
            f"{'-' if angle is None else f'{angle:.1f} deg'}; {report.get('seconds', 0.0):.2f} s.")
    if tolerance > final_tolerance:
        text += f" (Previewed at tolerance {tolerance:.3g} mm; OK rounds at {final_tolerance:.3g} mm.)"
    note = api.quality_note(report)
    return f"{text} {note}" if note else text


def _operation_code(operation):
    """make_rounding's operation argument, when it is not the default."""
    return "" if operation == ROUND else f", operation={operation!r}"


def _doc_expr(doc):
    return f"App.getDocument({doc.Name!r})"


def _vectors_code(points):
    return "[" + ", ".join(f"App.Vector({p[0]!r}, {p[1]!r}, {p[2]!r})" for p in points) + "]"


def _radius_code(radius):
    if isinstance(radius, list):
        return "[" + ", ".join(f"(App.Vector({p.x!r}, {p.y!r}, {p.z!r}), {r!r})" for p, r in radius) + "]"
    return repr(radius)
