# A syntax error on line 4 (python_apps_test.py: a load error).
WORLD = "sites"

def APP(bee)
    pass
