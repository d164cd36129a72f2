"""Qt needs an application object before images are painted: an offscreen one, asked for by its
command line, not by QT_QPA_PLATFORM in os.environ, which every process the rest of the suite
starts would inherit (the workbench's desktop test then saw turtlesim and rviz start offscreen)."""
import pytest


@pytest.fixture(scope="session", autouse=True)
def qt_app():
    from PyQt5.QtWidgets import QApplication
    app = QApplication.instance() or QApplication(["turtlesim-unit-tests", "-platform", "offscreen"])
    yield app
