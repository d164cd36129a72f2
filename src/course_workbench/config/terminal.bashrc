# The workbench's terminals (JupyterLab's, started by `make jupyter`): bash with the course
# workspace and your own workspace ~/catkin_ws sourced, as on a lab PC whose ~/.bashrc does it.
# JupyterLab starts them from an environment of no catkin workspace (course_workbench.startup).
[ -r /etc/bash.bashrc ] && . /etc/bash.bashrc
[ -r "$HOME/.bashrc" ] && . "$HOME/.bashrc"
_workbench_config="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
. "$_workbench_config/workspace.bash"
# course-check (the self-check before submitting), from this package's bin/.
_workbench_bin="$(cd "$_workbench_config/../bin" && pwd)"
case ":$PATH:" in
  *":$_workbench_bin:"*) ;;
  *) PATH="$_workbench_bin:$PATH"; export PATH ;;
esac
unset _workbench_bin _workbench_config
# The desktop (<base>/desktop/): while it runs, DISPLAY names its X display, so the windows of
# what you type (turtlesim, rviz, rqt_plot, gui:=true) show on it; without it, no DISPLAY
# (turtlesim then runs without a window, as the lab page wants). Its X session writes its display
# to COURSE_WORKBENCH_DISPLAY_FILE; this looks before every command, so a terminal opened before
# the desktop follows it too (a DEBUG trap: bash runs it before each command, keeping $?).
_workbench_display() {
  local shown=""
  if [ -r "${COURSE_WORKBENCH_DISPLAY_FILE:-}" ]; then read -r shown < "$COURSE_WORKBENCH_DISPLAY_FILE"; fi
  if [ -n "$shown" ] && [ -S "/tmp/.X11-unix/X${shown#:}" ]; then
    [ "${DISPLAY:-}" = "$shown" ] || export DISPLAY="$shown"
    _workbench_shown="$shown"
  elif [ -n "${_workbench_shown:-}" ] && [ "${DISPLAY:-}" = "$_workbench_shown" ]; then
    unset DISPLAY _workbench_shown  # the desktop stopped: only the DISPLAY set here goes
  fi
}
trap _workbench_display DEBUG
