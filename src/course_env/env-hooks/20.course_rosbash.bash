# roscd, rosls, roscp, rosed, roscat: Debian ships rosbash's shell functions only as a
# bash-completion file, which a non-login or scripted shell never reads. Source it here.
if [ -n "${BASH_VERSION:-}" ] && ! declare -F roscd >/dev/null 2>&1 \
   && [ -r /usr/share/bash-completion/completions/rosbash ]; then
  . /usr/share/bash-completion/completions/rosbash
fi
