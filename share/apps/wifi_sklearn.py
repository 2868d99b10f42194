# Case 2 of paper 000 (§5.1.2) the way BeeCluster's own sample does it: map a Wi-Fi field with
# scikit-learn's Gaussian process, sensing next where the map is least sure (its predictive
# standard deviation), a few cells at a time, until every cell's is below the world's
# cancel_below_db; the map is the GP's mean over the cells. Needs Debian's python3-sklearn.
# swath-fleet run share/apps/wifi_sklearn.py --world rf_field --drones 2 -o OUT
import os

# numpy's BLAS and OpenMP split sums over threads by the machine's core count, which changes the
# last bits of a fit and so, at a tie, where the app senses next: one thread keeps the same seed's
# events the same bytes on every machine. Set before numpy is first imported, and limited again
# below in case something imported it already.
for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import numpy as np  # noqa: E402
from sklearn.gaussian_process import GaussianProcessRegressor  # noqa: E402
from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel  # noqa: E402

try:
    from threadpoolctl import threadpool_limits  # noqa: E402

    threadpool_limits(1)
except ImportError:  # Debian's python3-sklearn depends on it; the variables above still hold
    pass

WORLD = "rf_field"
BATCH = 4  # cells sensed at once: tasks the scheduler shares among the drones
RANDOM_STATE = 0  # the GP's own draws (sample_y): fixed, so nothing in it varies run to run


def kernel(w):
    """The world's prior (the built-in app's): σ_f² · RBF(ℓ) + σ_n² (dB², metres)."""
    return ConstantKernel(w.gp_sigma_f**2, "fixed") * RBF(w.gp_length_m, "fixed") + \
        WhiteKernel(w.gp_sigma_n_db**2, "fixed")


def cells(w):
    """The centres of the cell_m grid over the fence, row by row from the south-west (x, y, m)."""
    x0 = min(p[0] for p in w.fence)
    y0 = min(p[1] for p in w.fence)
    nx = max(1, int(np.floor(w.width_m / w.cell_m + 1e-9)))
    ny = max(1, int(np.floor(w.height_m / w.cell_m + 1e-9)))
    return [(x0 + (i + 0.5) * w.cell_m, y0 + (j + 0.5) * w.cell_m) for j in range(ny) for i in range(nx)]


def latent_sd(gp, xy):
    """The map's own uncertainty at xy, dB: sklearn's std includes the WhiteKernel's reading noise,
    which no number of readings removes, so it is taken out."""
    _, sd = gp.predict(np.asarray(xy, dtype=float), return_std=True)
    noise = gp.kernel_.k2.noise_level
    return np.sqrt(np.maximum(sd**2 - noise, 0.0))


def uncertainty(w, sensed_xy, xy):
    """Latent sd at xy with the prior's hyperparameters after readings at sensed_xy: it does not
    depend on the values read, so cells still being sensed count as known (a batch spreads out)."""
    gp = GaussianProcessRegressor(kernel(w), optimizer=None)
    if not sensed_xy:
        return np.full(len(xy), w.gp_sigma_f)
    gp.fit(np.asarray(sensed_xy, dtype=float), np.zeros(len(sensed_xy)))
    return latent_sd(gp, xy)


def next_cells(w, grid, chosen):
    """Up to BATCH unsensed cells, each the least certain given the ones before it; none once every
    cell's sd is below cancel_below_db."""
    batch = []
    for _ in range(BATCH):
        known = [grid[i] for i in chosen + batch]
        sd = uncertainty(w, known, grid)
        sd[chosen + batch] = -1.0
        i = int(np.argmax(sd))  # the first of equals: deterministic
        if sd[i] < w.cancel_below_db:
            break
        batch.append(i)
    return batch


def fit_map(w, xy, values_db):
    """The final map: sklearn's GP with the world's prior (the built-in app's hyperparameters),
    prior mean the readings' mean. Kept, not fitted: on a few dozen readings maximum likelihood
    takes the shadowing near an access point for noise (σ_n near 4 dB where the sensor's is 2)
    and its map is worse (docs/swath-fleet.md)."""
    gp = GaussianProcessRegressor(kernel(w), optimizer=None, random_state=RANDOM_STATE)
    v = np.asarray(values_db, dtype=float)
    gp.fit(np.asarray(xy, dtype=float), v - v.mean())
    return gp, float(v.mean())


def predict_map(gp, mean_db, xy):
    """The map's RSSI at xy, dBm."""
    return gp.predict(np.asarray(xy, dtype=float)) + mean_db


def sense_cell(bee, x, y):
    bee.act("fly_to", x, y, 0.0)
    return bee.act("sense", "rssi").value


def APP(bee):
    w = bee.world
    grid = cells(w)
    chosen, xy, values = [], [], []
    while True:
        batch = next_cells(w, grid, chosen)
        if not batch:
            break
        tasks = [bee.newTask(sense_cell, *grid[i], kind="wifi-cell") for i in batch]
        for t in tasks:  # in the order asked, whatever order they finish in
            r = t.value
            xy.append((r.at[0], r.at[1]))
            values.append(r.values[0])
        chosen += batch
    gp, mean_db = fit_map(w, xy, values)
    bee.metric("cells", len(grid))
    bee.metric("cells_sensed", len(chosen))
    bee.metric("map_mean_dbm", float(np.mean(predict_map(gp, mean_db, grid))))
    bee.metric("map_sd_max_db", float(np.max(latent_sd(gp, grid))))
