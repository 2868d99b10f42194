# Case 2 of paper 000 (§5.1.2) in BeeCluster's API: map a Wi-Fi field cell by cell; each reading
# updates a Gaussian process, and the cells it already knows well enough are cancelled.
# swath-fleet run share/apps/wifi.py --world rf_field --drones 2 -o OUT
import math

from swath_fleet import GaussianProcess, TaskCancelled

WORLD = "rf_field"
NAME = "wifi"  # logs as the built-in app: the same events.jsonl for the same seed


class WifiMap:
    def __init__(self, w):
        self.gp = GaussianProcess(w.gp_length_m, w.gp_sigma_f, w.gp_sigma_n_db)
        self.cells, self.tasks, self.open = [], [], []  # open: neither sensed nor cancelled


def wifi_cell(bee, i, m, below_db):
    bee.act("fly_to", *m.cells[i])
    r = bee.act("sense", "rssi").value
    m.open[i] = False
    m.gp.add(r.at[0], r.at[1], r.values[0])
    # Cells the map now knows well enough are not worth a flight: cancel them.
    for j, (x, y, _) in enumerate(m.cells):
        if m.open[j] and m.gp.predict(x, y)[1] < below_db:
            m.open[j] = False
            bee.cancelTasks([m.tasks[j]])


def APP(bee):
    w = bee.world
    m = WifiMap(w)
    x0 = y0 = 1e18
    for p in w.fence:
        x0, y0 = min(x0, p[0]), min(y0, p[1])
    nx = max(1, int(math.floor(w.width_m / w.cell_m + 1e-9)))
    ny = max(1, int(math.floor(w.height_m / w.cell_m + 1e-9)))
    for j in range(ny):
        for i in range(nx):
            m.cells.append((x0 + (i + 0.5) * w.cell_m, y0 + (j + 0.5) * w.cell_m, 0.0))
    m.open = [True] * len(m.cells)
    for i in range(len(m.cells)):
        m.tasks.append(bee.newTask(wifi_cell, i, m, w.cancel_below_db, kind="wifi-cell"))
    cancelled = 0
    for t in m.tasks:
        try:
            t.value
        except TaskCancelled:
            cancelled += 1
    bee.metric("cells", len(m.cells))
    bee.metric("cells_cancelled", cancelled)
