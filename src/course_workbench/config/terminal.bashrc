# The workbench's terminals (JupyterLab's, started by `make jupyter`): bash with the course
# workspace and your own workspace ~/catkin_ws sourced, as on a lab PC whose ~/.bashrc does it.
# JupyterLab starts them from an environment of no catkin workspace (course_workbench.startup).
[ -r /etc/bash.bashrc ] && . /etc/bash.bashrc
[ -r "$HOME/.bashrc" ] && . "$HOME/.bashrc"
if [ -r "${COURSE_WORKBENCH_SETUP:-}" ]; then
  . "$COURSE_WORKBENCH_SETUP"
else
  echo "workbench: the course workspace's setup.bash (${COURSE_WORKBENCH_SETUP:-unset}) is missing: run make build" >&2
fi
if [ -r "${COURSE_WORKBENCH_OVERLAY:-}/devel/setup.bash" ]; then
  . "$COURSE_WORKBENCH_OVERLAY/devel/setup.bash"
fi
# course-check (the self-check before submitting), from this package's bin/.
_workbench_bin="$(cd "$(dirname "${BASH_SOURCE[0]}")/../bin" && pwd)"
case ":$PATH:" in
  *":$_workbench_bin:"*) ;;
  *) PATH="$_workbench_bin:$PATH"; export PATH ;;
esac
unset _workbench_bin
