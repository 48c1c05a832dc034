"""The checks the Round edges task panel shows beside its fields: the largest radius the picked chains take
(max_radius), the stamping rule r >= k.t, the corners where picked chains meet (plan_arrays), and whether the
radius field is in use.  A mixin of RoundEdgesPanel (round_edges.py): it reads the panel's seeds, law,
chains and form."""
from .. import api, radius_limits
from ..errors import RoundingError
from . import overlays
from .round_edges_form import quantity_value


class RadiusChecks:
    """The radius limit, rule line, corner plan and radius field state of RoundEdgesPanel."""

    def _measure_limits(self):
        """The largest radius of each picked chain (max_radius; a fraction of a second), shown beside the
        radius field."""
        self.limits = []
        if self.seeds and not self.form.existing_round():  # an existing round's limit is its sharp edge's: not known here
            try:
                self.limits = radius_limits.max_radius_arrays(self.vertices, self.triangles, self.seeds,
                                                              self.feature_angle(), self.form.reach.value())
            except RoundingError:
                pass  # the trace's own error is shown already
        self._show_limit()

    def _plan_corners(self):
        """Where the picked chains meet and how each corner will be blended (api.plan_arrays), shown under the
        seeds; the corner round_edges would refuse, in red, with its reason."""
        self.plan = None
        fault = ""  # a flaw of the mesh at a corner (a flipped facet there), which no other line shows
        if len(self.chain_wires) > 1 and not self.form.existing_round():
            try:
                p = self.parameters()
                self.plan = api.plan_arrays(self.vertices, self.triangles, p["seeds"], p["radius"], p["tolerance"],
                                            p["feature_angle"], p["reach"])
            except RoundingError as e:
                fault = str(e) if e.code == "non_manifold_input" else ""  # others: the trace's own, shown already
            except ValueError:
                pass  # the table's own error is shown already
        if fault:
            self.form.show_corners("Corner not blended: " + fault, error=True)
        else:
            self.form.show_corners(self.plan.summary() if self.plan else "", error=bool(self.plan and self.plan.refusal))

    def corner_marks(self):
        """[(point, color)]: a marker per corner of the plan, coloured by its blend."""
        return [(tuple(c["vertex"]), overlays.CORNER_COLORS[c["kind"]]) for c in self.plan.corners] if self.plan else []

    def radius_past_limit(self):
        """'' or the sentence saying the constant radius is past the largest that fits (and why)."""
        if self.law or not self.limits:
            return ""
        radius = quantity_value(self.form.radius)
        tightest = min(self.limits, key=lambda lim: lim.radius)
        if radius <= tightest.radius:
            return ""
        return f"r = {radius:g} mm is too large: the largest that fits is {tightest.radius:.4g} mm ({tightest.reason})"

    def _show_limit(self):
        past = self.radius_past_limit()
        if past:
            self.form.show_limit(past, error=True)
        elif self.limits:
            tightest = min(self.limits, key=lambda lim: lim.radius)
            self.form.show_limit(f"{tightest.radius:.4g} mm ({radius_limits.WHY_TEXT.get(tightest.why, tightest.why)})")
        else:
            self.form.show_limit("")
        self._show_rules()

    def rule_check(self):
        """check_rules' rows for the radius (a law's smallest), the sheet thickness and the tool type, against
        the picked chains' limits; [] when there is nothing to check (no chain, or no thickness and no limit)."""
        thickness = quantity_value(self.form.thickness) or None
        limits = None if self.law else (self.limits or None)
        if not self.seeds or (thickness is None and limits is None):
            return []
        radius = min(row[3] for row in self.law) if self.law else quantity_value(self.form.radius)
        try:
            return radius_limits.check_rules(limits, radius, thickness, self.form.tool_type())
        except RoundingError:
            return []  # a radius of 0: the preview says why

    def _show_rules(self):
        """The rule line beside the limit (radius_limits.rule_line: the flags and why in red, or that the k.t
        rule is met), and what the automatic tolerance is for the radius."""
        self.form.show_rules(*radius_limits.rule_line(self.rule_check(), self.form.tool_type()))
        largest = max((row[3] for row in self.law), default=0.0) if self.law else quantity_value(self.form.radius)
        self.form.show_automatic_tolerance(largest)

    def _update_radius_field(self):
        """The constant radius is unused with a radius law, and fixed by an expression if it has one."""
        if self._radius_expression:
            reason = f"Radius is set by the expression {self._radius_expression}"
        elif self.law:
            reason = "The variable radius table is used; empty it to use a constant radius"
        else:
            reason = None
        self.form.radius.setEnabled(reason is None)
        self.form.radius.setToolTip(reason or "Rolling ball radius")
        self._show_rules()  # the rule line and the automatic tolerance follow the radius (or the law)
