"""What the workbench's start-up and roslab both need: the student's default master and the
variable carrying the lab page's token.

In a module of their own because roslab runs in every student's container for as long as the lab
page is open: taking them from `startup` made it import rospkg and course_sandbox too, 2.3 MiB of
resident memory it never uses.
"""
DEFAULT_MASTER_URI = "http://localhost:11311"
TOKEN_VAR = "COURSE_WORKBENCH_TOKEN"  # the lab page's copy of Jupyter's token (roslab only)
