# Case 4 of paper 000 (§5.2.1) in BeeCluster's API: a delivery A→F, photos at B and E and a video
# from C to D sharing the fleet; the delivery and the video each keep one drone.
# swath-fleet run share/apps/multiplexing.py --world sites --drones 1 -o OUT

WORLD = "sites"
NAME = "multiplexing"  # logs as the built-in app: the same events.jsonl for the same seed


def delivery(bee, a, b, handling_s):
    bee.act("fly_to", *a)
    bee.act("custom", "pick_up", handling_s)
    bee.act("fly_to", *b)
    bee.act("custom", "drop", handling_s).value


def photo(bee, at):
    bee.act("fly_to", *at)
    bee.act("sense", "camera").value


def video(bee, a, b):
    bee.act("fly_to", *a)
    bee.act("custom", "video_start", 1.0)
    bee.act("fly_to", *b)
    bee.act("custom", "video_stop", 1.0).value


def APP(bee):
    w = bee.world
    s = w.sites
    d = bee.newTask(delivery, s["A"], s["F"], w.handling_s, kind="delivery", same_drone=True,
                    interruptible=w.delivery_interruptible)
    b = bee.newTask(photo, s["B"], kind="photo")
    e = bee.newTask(photo, s["E"], kind="photo")
    v = bee.newTask(video, s["C"], s["D"], kind="video", same_drone=True, interruptible=False)
    for t in (d, b, e, v):
        t.value
