"""The widgets of the Round edges task panel (layout only; behaviour is in round_edges.py)."""
import FreeCADGui
from PySide import QtCore, QtGui

from .. import errors, inputs, radius_limits
from ..objects.rounding import CHANGE_RADIUS, ROUND

PICK_SEED, PICK_LAW_POINT = "seed", "law"
# what a click picks -> the Rounding's Operation it makes, and the panel's title and hint in that mode
PICK_TARGETS = {"Sharp edges": ROUND, "Existing round": CHANGE_RADIUS}
TITLES = {ROUND: "Round sharp edges", CHANGE_RADIUS: "Change round radius"}
HINTS = {ROUND: "Click on the mesh next to a sharp edge: its whole chain is selected.",
         CHANGE_RADIUS: "Click on an existing round: it is recognised, its radius measured, and it is made "
                        "again at the radius below (0: sharp)."}
LAW_COLUMNS = ("X", "Y", "Z", "Radius")


def quantity_box(unit, value, minimum=0.0, maximum=1e9, tooltip=""):
    """A Gui::QuantitySpinBox (units, expressions, unit conversion as in FreeCAD's own panels)."""
    box = FreeCADGui.UiLoader().createWidget("Gui::QuantitySpinBox")
    box.setProperty("unit", unit)
    box.setProperty("minimum", minimum)
    box.setProperty("maximum", maximum)
    box.setProperty("rawValue", value)
    box.setToolTip(tooltip)
    return box


def quantity_value(box):
    """The value of a QuantitySpinBox in FreeCAD's base unit (mm, degrees)."""
    return float(box.property("rawValue"))


class RoundEdgesForm(QtGui.QWidget):
    """Seeds list, pick mode, radius (constant or law table), options, preview switch, status line."""

    def __init__(self, radius, tolerance, feature_angle, reach, thickness, tool, operation=ROUND):
        super().__init__()
        self.setWindowTitle(TITLES[operation])
        layout = QtGui.QVBoxLayout(self)
        layout.addWidget(self._edges_group(operation))
        layout.addWidget(self._radius_group(radius, thickness, tool))
        layout.addWidget(self._options_group(tolerance, feature_angle, reach))
        self.live_preview = QtGui.QCheckBox("Live preview")
        self.live_preview.setChecked(True)
        layout.addWidget(self.live_preview)
        self.status = QtGui.QLabel()
        self.status.setWordWrap(True)
        self.status.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        layout.addWidget(self.status)
        layout.addStretch()

    def _edges_group(self, operation):
        group = QtGui.QGroupBox("Edges")
        layout = QtGui.QVBoxLayout(group)
        row = QtGui.QFormLayout()
        self.pick_target = QtGui.QComboBox()
        self.pick_target.addItems(list(PICK_TARGETS))
        self.pick_target.setCurrentIndex(list(PICK_TARGETS.values()).index(operation))
        self.pick_target.setToolTip("Sharp edges: round them.  Existing round: change its radius (the Rounding's "
                                    "Operation).")
        row.addRow("Pick:", self.pick_target)
        layout.addLayout(row)
        self.hint = QtGui.QLabel(HINTS[operation])
        self.hint.setWordWrap(True)
        layout.addWidget(self.hint)
        self.pick_target.currentIndexChanged.connect(lambda *_: self.hint.setText(self.pick_hint()))
        self.seed_list = QtGui.QListWidget()
        self.seed_list.setSelectionMode(QtGui.QAbstractItemView.ExtendedSelection)
        self.seed_list.setMaximumHeight(90)
        layout.addWidget(self.seed_list)
        buttons = QtGui.QHBoxLayout()
        self.remove_seed_button = QtGui.QPushButton("Remove")
        self.clear_seeds_button = QtGui.QPushButton("Clear")
        buttons.addWidget(self.remove_seed_button)
        buttons.addWidget(self.clear_seeds_button)
        layout.addLayout(buttons)
        # where the picked chains meet, how each corner will be blended (or the one that would be refused)
        self.corners = QtGui.QLabel("")
        self.corners.setWordWrap(True)
        layout.addWidget(self.corners)
        self.found = QtGui.QLabel("")  # "Existing round": the radius each picked round has
        self.found.setWordWrap(True)
        layout.addWidget(self.found)
        layout.addWidget(QtGui.QLabel("A click on the mesh adds:"))
        self.pick_seed = QtGui.QRadioButton("an edge to round")
        self.pick_law = QtGui.QRadioButton("a variable-radius point")
        self.pick_seed.setChecked(True)
        layout.addWidget(self.pick_seed)
        layout.addWidget(self.pick_law)
        return group

    def _radius_group(self, radius, thickness, tool):
        group = QtGui.QGroupBox("Radius")
        layout = QtGui.QVBoxLayout(group)
        row = QtGui.QFormLayout()
        self.radius = quantity_box("mm", radius, minimum=0.0,
                                   tooltip="Rolling ball radius (used when the table below is empty)")
        row.addRow("Radius:", self.radius)
        # the largest radius the picked chains take (max_radius), and why: next to the field it limits
        self.radius_limit = QtGui.QLabel("")
        self.radius_limit.setWordWrap(True)
        row.addRow("Largest:", self.radius_limit)
        # the stamping rule r >= k.t (radius_limits.check_rules) for a sheet thickness t and the tool's k
        rule = ", ".join(f"{name} r >= {k:g} t" for name, k in radius_limits.DEFAULT_K.items())
        self.thickness = quantity_box("mm", thickness, tooltip=f"Sheet thickness t for the rule ({rule}); "
                                                               "0: no rule check")
        row.addRow("Sheet thickness (0 = no rule check):", self.thickness)
        self.tool = QtGui.QComboBox()
        self.tool.addItems(list(radius_limits.DEFAULT_K))
        self.tool.setCurrentText(tool)
        self.tool.setToolTip(f"The tool the radius is on: {rule}")
        row.addRow("Tool:", self.tool)
        self.rule_check = QtGui.QLabel("")
        self.rule_check.setWordWrap(True)
        row.addRow("Rules:", self.rule_check)
        layout.addLayout(row)
        law_hint = QtGui.QLabel("Variable radius: with \"a variable-radius point\" checked, click near the "
                                "chain; each point lands on the chain (empty table: constant radius).")
        law_hint.setWordWrap(True)
        layout.addWidget(law_hint)
        self.law_table = QtGui.QTableWidget(0, len(LAW_COLUMNS))
        self.law_table.setHorizontalHeaderLabels(LAW_COLUMNS)
        header = self.law_table.horizontalHeader()
        header.setMinimumSectionSize(30)  # the panel must fit a narrow combo view
        header.setSectionResizeMode(QtGui.QHeaderView.Stretch)
        self.law_table.verticalHeader().hide()
        self.law_table.setMaximumHeight(130)
        layout.addWidget(self.law_table)
        self.remove_law_button = QtGui.QPushButton("Remove radius point")
        layout.addWidget(self.remove_law_button)
        return group

    def _options_group(self, tolerance, feature_angle, reach):
        group = QtGui.QGroupBox("Options")
        layout = QtGui.QFormLayout(group)
        # A plain spin box: at 0 it says what automatic is (show_automatic_tolerance), which
        # Gui::QuantitySpinBox cannot (it ignores Qt's special-value text).
        self.tolerance = QtGui.QDoubleSpinBox()
        self.tolerance.setRange(0.0, 1e6)
        self.tolerance.setDecimals(3)
        self.tolerance.setSingleStep(0.01)
        self.tolerance.setSuffix(" mm")
        self.tolerance.setValue(tolerance)
        self.tolerance.setToolTip(f"Chordal tolerance; 0 = radius / {1 / inputs.AUTO_TOLERANCE_FRACTION:g}")
        self.feature_angle = quantity_box("deg", feature_angle, minimum=1.0, maximum=179.0,
                                          tooltip="An edge is sharp when its facets turn by at least this")
        self.reach = QtGui.QDoubleSpinBox()
        self.reach.setRange(errors.core.MIN_REACH if errors.core else 1.0, 20.0)  # the engine's own limit
        self.reach.setSingleStep(0.5)
        self.reach.setValue(reach)
        self.reach.setToolTip("Facets within reach x radius of a chain are re-meshed")
        layout.addRow("Tolerance (0 = automatic, radius / 100):", self.tolerance)
        layout.addRow("Feature angle:", self.feature_angle)
        layout.addRow("Reach:", self.reach)
        return group

    # ---------------------------------------------------------------- reading and writing values
    def operation(self):
        """The Rounding Operation the pick target makes (objects.rounding ROUND or CHANGE_RADIUS)."""
        return PICK_TARGETS[self.pick_target.currentText()]

    def existing_round(self):
        return self.operation() == CHANGE_RADIUS

    def pick_hint(self):
        return HINTS[self.operation()]

    def show_found(self, text):
        self.found.setText(text)

    def pick_mode(self):
        return PICK_LAW_POINT if self.pick_law.isChecked() else PICK_SEED

    def show_seeds(self, seeds):
        self.seed_list.clear()
        for number, p in enumerate(seeds, 1):
            self.seed_list.addItem(f"{number}: ({p.x:.2f}, {p.y:.2f}, {p.z:.2f})")

    def selected_seed_rows(self):
        return sorted({index.row() for index in self.seed_list.selectedIndexes()})

    def show_law(self, rows):
        """Fill the table with (x, y, z, r) rows, without firing its change signal."""
        blocked = self.law_table.blockSignals(True)
        self.law_table.setRowCount(len(rows))
        for i, row in enumerate(rows):
            for j, value in enumerate(row):
                self.law_table.setItem(i, j, QtGui.QTableWidgetItem(f"{value:.3f}"))
        self.law_table.blockSignals(blocked)

    def law_rows(self):
        """[(x, y, z, r)] from the table; ValueError names the cell that is not a number."""
        rows = []
        for i in range(self.law_table.rowCount()):
            row = []
            for j, column in enumerate(LAW_COLUMNS):
                item = self.law_table.item(i, j)
                text = item.text() if item else ""
                try:
                    row.append(float(text))
                except ValueError:
                    raise ValueError(f"radius point {i + 1}: {column} is not a number: {text!r}") from None
            rows.append(tuple(row))
        return rows

    def selected_law_rows(self):
        return sorted({index.row() for index in self.law_table.selectedIndexes()})

    def show_limit(self, text, error=False):
        """The radius limit beside the radius field; in red when the radius is past it."""
        self.radius_limit.setStyleSheet("color: #c00000; font-weight: bold;" if error else "")
        self.radius_limit.setText(text)

    def tool_type(self):
        return self.tool.currentText()

    def show_rules(self, text, error=False):
        """The rule check beside the radius limit; in red when a rule is broken."""
        self.rule_check.setStyleSheet("color: #c00000; font-weight: bold;" if error else "")
        self.rule_check.setText(text)

    def show_automatic_tolerance(self, largest_radius):
        """What a tolerance of 0 means for this radius, shown in the field at 0."""
        self.tolerance.setSpecialValueText(
            f"automatic (r / {1 / inputs.AUTO_TOLERANCE_FRACTION:g} = "
            f"{inputs.automatic_tolerance(largest_radius):.3g} mm)")

    def show_corners(self, text, error=False):
        """The picked chains' corners and their blends; in red for a corner that would be refused."""
        self.corners.setStyleSheet("color: #c00000;" if error else "")
        self.corners.setText(text)

    def show_status(self, text, error=False):
        self.status.setStyleSheet("color: #c00000; font-weight: bold;" if error else "")
        self.status.setText(text)
