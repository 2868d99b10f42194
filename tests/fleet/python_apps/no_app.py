# Defines no APP (python_apps_test.py: a load error).
WORLD = "sites"
