"""What a milestone's check and the grader need at run time, and nothing a test alone needs: wait
for a condition (waiting), record topics and /rosout (recorders), start a node (nodes) or type
into one (keyboard), keep a run's artifacts without following links (artifacts), run a rostest
file apart from other runs (rostest_runner, isolation, core_params) and read its JUnit report
(junit). The test harnesses (browsers, hubs, screens, fuzzing) are course_testkit's."""
