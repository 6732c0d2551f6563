# LiftRemesh add-on, application part: FreeCAD runs this at start-up (GUI or not). The macro API
# is the package `LiftRemesh` beside this file (import LiftRemesh); nothing to register here.
