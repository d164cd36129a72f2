"""The students workbench: JupyterLab with the courses terminals and the lab page (make jupyter)."""
