"""Run untrusted student code in a sandbox: see course_sandbox.run for the one entry point."""
