"""The S-rail die part of the GUI macro: the progress indicator, and the live preview's speed on a die of
147k facets (picking a shoulder, previews at several radii as a user types them, OK)."""
import statistics
import time

import FreeCAD
import FreeCADGui
from PySide import QtGui

from gui_support import StatusSampler, press_task_button, redraw_seconds, screenshot, step, wait_until

PREVIEW_RADII = (5.5, 6.0, 4.5, 4.0, 5.0)  # as typed, one after another (5 is the default)
LONGEST_RUN_S = 10.0  # the progress check's stand-in engine call, at most


def run():
    check_progress_indicator()
    preview_on_the_die()


def check_progress_indicator():
    """A long engine call runs under FreeCAD's progress indicator: status text, the progress bar after
    FreeCAD's 2 s delay, and a window that keeps processing events.  The engine's stand-in sleeps on the
    worker thread, releasing the GIL as the engine does, until the bar has shown for a while or
    LONGEST_RUN_S have passed: one slow repaint on a loaded machine cannot end the run before the bar's
    delay, and a bar that never shows still fails the test."""
    from MeshRound import progress
    # nothing left over from the steps before may write the status bar meanwhile: no preselection under
    # the pointer, no queued status message
    FreeCADGui.Selection.clearPreselection()
    QtGui.QCursor.setPos(0, 0)
    FreeCADGui.updateGui()
    # nor may a bar still show from a step before (on a loaded machine one was seen 0.66 s into the run):
    # the run starts once FreeCAD has hidden it
    bars = FreeCADGui.getMainWindow().statusBar().findChildren(QtGui.QProgressBar)
    waited = time.perf_counter()
    while any(b.isVisible() for b in bars) and time.perf_counter() - waited < LONGEST_RUN_S:
        FreeCADGui.updateGui()
        time.sleep(0.05)
    bar_before = any(b.isVisible() for b in bars)
    sampler = StatusSampler()
    started = time.perf_counter()

    def long_engine_call():
        while time.perf_counter() - started < LONGEST_RUN_S:
            shown = sampler.bar_first_seen
            if shown is not None and time.perf_counter() - shown > 0.5:
                return
            time.sleep(0.05)

    with progress.busy("Rounding edges of a long chain"):
        sampler.sample()  # what the status bar shows as the run starts
        progress.wait_for(long_engine_call)
    seconds = time.perf_counter() - started
    sampler.stop()
    step("progress", {"seconds": seconds, "samples": len(sampler.samples), "messages": sampler.messages(),
                      "bar_seen": sampler.bar_seen(), "bar_before": bar_before,
                      "bar_delay": None if sampler.bar_first_seen is None else sampler.bar_first_seen - started,
                      "bar_after": sampler.bar_visible()})


def preview_on_the_die():
    import die_meshes
    from MeshRound import meshconv
    from MeshRound.taskpanels.round_edges import active_panel

    vertices, triangles, seeds = die_meshes.die_arrays(4)
    doc = FreeCAD.newDocument("DieTest")
    die = doc.addObject("Mesh::Feature", "Die")
    die.Mesh = meshconv.arrays_to_mesh(vertices, triangles)
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    frame_of_die = redraw_seconds(view)

    FreeCADGui.Selection.addSelection(doc.Name, die.Name)
    started = time.perf_counter()
    FreeCADGui.runCommand("MeshRound_RoundEdges")
    panel_open = time.perf_counter() - started
    panel = active_panel()
    redraw_seconds(view)  # the first frame with the ghosted die

    started = time.perf_counter()
    panel.add_seed(seeds[0])
    pick = time.perf_counter() - started
    pick_frame = redraw_seconds(view)

    previews = []
    for radius in PREVIEW_RADII:
        panel.result, panel.error = None, None
        started = time.perf_counter()
        panel.set_radius(radius)  # as typed: the debounced live preview follows
        latency = wait_until(lambda: panel.result is not None or panel.error is not None)
        report = panel.result.report if panel.result else {}
        previews.append({"radius": radius, "latency_s": latency, "frame_s": redraw_seconds(view),
                         "engine_s": report.get("seconds_total"), "round_arrays_s": report.get("seconds"),
                         "facets_added": report.get("facets_added"), "error": panel.error})
    screenshot("gui_die_preview.png")
    latencies = [p["latency_s"] for p in previews if p["latency_s"] is not None and not p["error"]]

    sampler_ok = StatusSampler()
    started = time.perf_counter()
    press_task_button("ok")
    ok_seconds = time.perf_counter() - started
    sampler_ok.stop()
    rounding = next((o for o in doc.Objects if o.TypeId == "Mesh::FeaturePython"), None)
    step("die", {
        "facets": die.Mesh.CountFacets, "frame_of_die_s": frame_of_die, "panel_open_s": panel_open,
        "pick_s": pick, "pick_frame_s": pick_frame, "chains": len(panel.chain_wires),
        "previews": previews, "median_latency_s": statistics.median(latencies) if latencies else None,
        "ok_s": ok_seconds, "ok_messages": sampler_ok.messages(),
        "ok_samples": len(sampler_ok.samples),
        "rounding_state": rounding.State if rounding else None,
        "rounding_statistics": dict(rounding.Statistics) if rounding else None})
