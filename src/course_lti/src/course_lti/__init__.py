"""Grades back to the LMS through LTI Advantage Assignment and Grade Services (AGS 2.0), with no ROS.

config (the tool's registration with the platform: lti.yaml), users (who each student is in the
LMS), scores (a grading's results.json as the scores to post), token (the client-credentials
grant, its JWT signed by the tool's key), transport (HTTP with retries and backoff), ags (line
items and scores), record (what was posted, what is pending) and post (one posting run, its
dry run and its summary). docs/grading.md, "Grades back to the LMS (LTI 1.3 AGS)".
"""
