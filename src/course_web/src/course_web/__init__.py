"""course_web: the lab in a browser (a rosbridge v2 websocket server and the page it serves)."""
