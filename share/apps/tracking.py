# Case 5 of paper 000 (§5.2.2) in BeeCluster's API: follow a walker, looking where it should be
# by now; drones with short flights hand over.
# swath-fleet run share/apps/tracking.py --world tracking --fleet FLEET -o OUT
from swath_fleet import ActionFailed, hypot

WORLD = "tracking"
NAME = "tracking"  # logs as the built-in app: the same events.jsonl for the same seed


def sense_at(bee, x, y, sensor):
    bee.act("fly_to", x, y, 0.0)
    return bee.act("sense", sensor).value


def APP(bee):
    w = bee.world
    lx, ly = w.start[0], w.start[1]
    vx = vy = t_last = seen_s = longest_gap = 0.0
    looks = hits = handoffs = 0
    last_drone = -1
    while bee.now_s < w.duration_s:
        ahead = min(bee.now_s - t_last + 2.0, 10.0)  # beyond: a guess
        asked_s = bee.now_s
        look = bee.newTask(sense_at, lx + vx * ahead, ly + vy * ahead, "camera",
                           kind="tracking-look")
        try:
            r = look.value
        except ActionFailed:
            # A look lost on the way: look again. One refused at once (the walker left the
            # fence) would be refused again at the same instant, forever: stop following.
            if bee.now_s == asked_s:
                break
            continue
        looks += 1
        if last_drone >= 0 and r.drone != last_drone:
            handoffs += 1
        last_drone = r.drone
        if len(r.values) == 2:
            hits += 1
            if looks > 1 and r.t_s > t_last:
                vx = (r.values[0] - lx) / (r.t_s - t_last)
                vy = (r.values[1] - ly) / (r.t_s - t_last)
                v, cap = hypot(vx, vy), w.walker_speed_m_s
                if v > cap:
                    vx *= cap / v
                    vy *= cap / v
            longest_gap = max(longest_gap, r.t_s - seen_s)
            seen_s = t_last = r.t_s
            lx, ly = r.values[0], r.values[1]
    longest_gap = max(longest_gap, bee.now_s - seen_s)
    bee.metric("looks", looks)
    bee.metric("tracked_share", hits / looks if looks > 0 else 0.0)
    bee.metric("longest_gap_s", longest_gap)
    bee.metric("handoffs", handoffs)
