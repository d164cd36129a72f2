# The course workspace and the student's overlay ~/catkin_ws, sourced: what the workbench's
# terminals (terminal.bashrc) and its desktop's X session (desktop.xstartup) both start from.
# COURSE_WORKBENCH_SETUP and COURSE_WORKBENCH_OVERLAY come from the start-up (course_workbench.startup).
if [ -r "${COURSE_WORKBENCH_SETUP:-}" ]; then
  . "$COURSE_WORKBENCH_SETUP"
else
  echo "workbench: the course workspace's setup.bash (${COURSE_WORKBENCH_SETUP:-unset}) is missing: run make build" >&2
fi
if [ -r "${COURSE_WORKBENCH_OVERLAY:-}/devel/setup.bash" ]; then
  . "$COURSE_WORKBENCH_OVERLAY/devel/setup.bash"
fi
