# Case 3 of paper 000 (§5.1.3) in BeeCluster's API: find a signal source by sensing the corners
# of a square around the current place and stepping toward the strongest, `steps` times.
# swath-fleet run share/apps/hotspot.py --world hotspot --drones 4 -o OUT
# gives the same events.jsonl as the built-in app hotspot for the same seed.
from swath_fleet import hypot

WORLD = "hotspot"
NAME = "hotspot"  # logs as the built-in app: the same events.jsonl for the same seed


def sense_at(bee, x, y, sensor):
    bee.act("fly_to", x, y, 0.0)
    return bee.act("sense", sensor).value


def APP(bee):
    w = bee.world
    x, y = w.start[0], w.start[1]
    h = w.side_m / 2
    for _ in range(w.steps):
        corners = [(-h, -h), (h, -h), (h, h), (-h, h)]
        tasks = [bee.newTask(sense_at, x + dx, y + dy, "signal", kind="hotspot-corner")
                 for dx, dy in corners]
        readings = [t.value for t in tasks]
        best = max(readings, key=lambda r: r.values[0])  # the first of equals, as max_element
        dx, dy = best.at[0] - x, best.at[1] - y
        n = hypot(dx, dy)
        if n > 0:
            x, y = x + w.step_m * dx / n, y + w.step_m * dy / n
    sx, sy = w.source_m[0], w.source_m[1]
    bee.metric("final_distance_to_source_m", hypot(x - sx, y - sy))
    bee.metric("start_distance_to_source_m", hypot(w.start[0] - sx, w.start[1] - sy))
