# Case 1 of paper 000 (§5.1.1) in BeeCluster's API: trace a road step by step, each step where
# the last reading of the road camera says the road goes.
# swath-fleet run share/apps/road.py --world road --drones 3 -o OUT
import math

WORLD = "road"
NAME = "road"  # logs as the built-in app: the same events.jsonl for the same seed


def sense_at(bee, x, y, sensor):
    bee.act("fly_to", x, y, 0.0)
    return bee.act("sense", sensor).value


def APP(bee):
    w = bee.world
    x, y = w.road_m[0][0], w.road_m[0][1]
    for _ in range(w.steps):
        r = bee.newTask(sense_at, x, y, "road_camera", kind="road-step").value
        heading = (90.0 - r.values[2]) * math.pi / 180.0  # from +x, counter-clockwise, radians
        x = r.values[0] + w.step_m * math.cos(heading)
        y = r.values[1] + w.step_m * math.sin(heading)
    bee.metric("steps", w.steps)
