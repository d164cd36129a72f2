#!/bin/sh
# Run by CMakeLists.txt at configure time: try what a dishonest build could do.
escaped=""
course=$(rospack find course_milestones 2>/dev/null)
echo "course at: $course" >&2
if [ -n "$course" ] && touch "$course/PWNED_BY_CMAKE" 2>/dev/null; then escaped="$escaped write-course"; fi
out=$(awk '{print $5}' /proc/self/mountinfo | grep '/_work/' | head -n1 | sed 's|/_work/.*||')
echo "output folder seen as: $out" >&2
if [ -n "$out" ] && ls "$out/_work" 2>/dev/null | grep -qv '^attack_cmake_command$'; then escaped="$escaped see-other-students"; fi
if [ -n "$out" ] && [ -e "$out/report.html" -o -e "$out/bad_fork" ]; then escaped="$escaped see-grader-outputs"; fi
if [ "$(ps -e -o pid= | wc -l)" -gt 20 ]; then escaped="$escaped see-processes"; fi
pkill -9 -f rosmaster 2>/dev/null
pkill -9 -f turtlesim 2>/dev/null
echo "escaped:$escaped"
