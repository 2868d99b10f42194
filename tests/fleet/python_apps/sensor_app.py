# A sensor of the app's own (python_apps_test.py): "gas" reads x_m + 2 y_m + t_s in 7 s.
WORLD = "sites"


def gas(x_m, y_m, t_s):
    return [x_m + 2 * y_m + t_s]


SENSORS = {"gas": (7.0, gas)}


def sniff(bee, at):
    arrived = bee.act("fly_to", *at)
    r = bee.act("sense", "gas").value
    return arrived.value, r


def APP(bee):
    arrived, r = bee.newTask(sniff, bee.world.sites["B"]).value
    bee.metric("sense_s", r.t_s - arrived.t_s)
    bee.metric("error", r.values[0] - (r.at[0] + 2 * r.at[1] + r.t_s))  # t_s: the reading's time
