# A Python app whose task raises (python_apps_test.py looks for this file's line 9).
WORLD = "sites"


def photo(bee, at):
    bee.act("fly_to", *at)
    r = bee.act("sense", "camera").value
    scale = 0
    return r.t_s / scale


def APP(bee):
    bee.newTask(photo, bee.world.sites["B"]).value
