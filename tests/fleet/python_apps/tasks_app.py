# A Python app with tasks, futures and cancellation (python_apps_test.py). Random sleeps in every
# task's thread: the events must not depend on the threads' timing.
import random
import time

from swath_fleet import TaskCancelled

WORLD = "sites"


def jitter():
    time.sleep(random.random() * 0.004)  # unseeded on purpose


def photo(bee, at):
    jitter()
    bee.act("fly_to", *at)
    jitter()
    r = bee.act("sense", "camera").value
    jitter()
    return r.values


def loiter(bee, at, seconds):
    bee.act("fly_to", *at)
    jitter()
    bee.act("hover", seconds).value
    return "loitered"


def parcel(bee, a, b):
    bee.act("fly_to", *a)
    bee.act("custom", "pick_up", 3.0)
    bee.act("fly_to", *b)
    jitter()
    bee.act("custom", "drop", 3.0).value
    return "dropped"


def APP(bee):
    s = bee.world.sites
    photos = [bee.newTask(photo, s[n], kind="photo") for n in ("B", "E")]
    hold = bee.new_task(loiter, s["C"], 600.0, kind="loiter", interruptible=False)
    box = bee.newTask(parcel, s["A"], s["F"], kind="parcel", same_drone=True)
    values = [p.value for p in photos]  # blocks this task until both photos are taken
    jitter()
    bee.cancel_tasks([hold])
    try:
        hold.value
        bee.metric("cancel_seen", 0)
    except TaskCancelled:
        bee.metric("cancel_seen", 1)
    bee.metric("photos", len(values))
    bee.metric("parcel_dropped", 1 if box.value == "dropped" else 0)
