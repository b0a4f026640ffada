"""Tests of `import simbob_client` (python/simbob_client.py, copied into build/python beside the
module), run by ctest as python.pytest: key escaping both ways, and a version 3 session with a
simbob run that starts this test's own peer (run --controller)."""

import os
import subprocess
import sys
from pathlib import Path

import simbob_client
from simbob_client import escape_key, unescape_key

SIMBOB = os.path.abspath(os.environ.get("SIMBOB_BINARY", "build/simbob"))
SOURCE = Path(os.environ.get("SIMBOB_SOURCE_DIR", "."))


def test_the_module_is_the_one_beside_simbob():
    # PYTHONPATH=build/python: the copy CMake puts there, not the source file.
    assert Path(simbob_client.__file__).parent.name == "python"


def test_keys_escape_and_unescape():
    assert escape_key("Bot.Cart.Chassis") == "Bot.Cart.Chassis"
    assert escape_key("Bot.Mo tion") == "Bot.Mo%20tion"
    assert escape_key("Châssis, 1%") == "Ch%C3%A2ssis%2C%201%25"
    for key in ["Bot.Mo tion", "Châssis, 1%", "tab\there", "日本"]:
        assert unescape_key(escape_key(key)) == key
    assert unescape_key("Ch%c3%a2ssis") == "Châssis"


PEER = r"""
import sys
sys.path.insert(0, sys.argv[1])
from simbob_client import Client
c = Client.connect()
s = c.state()
print("version", c.version, "t", s.t, "bodies", len(s.bodies), "values", len(s.bodies["Bot.Cart.Châssis"]))
c.reply(subscribe={"bodies": ["Bot.Cart.Châssis"], "joints": []}, sets=[("Bot.Mo tion", 0.5, 0.0)])
s = c.state()
print("subscribed", sorted(s.bodies), len(s.joints))
c.reply(done=True)
"""


def test_a_version_3_session(tmp_path):
    scene = (SOURCE / "scenes" / "socket_robot.xml").read_text()
    scene = scene.replace('Key="Motion"', 'Key="Mo tion"').replace('Key="Chassis"', 'Key="Châssis"')
    (tmp_path / "keys.xml").write_text(scene)
    (tmp_path / "peer.py").write_text(PEER)
    module_dir = os.path.dirname(simbob_client.__file__)
    subprocess.run([SIMBOB, "run", "keys.xml", "--duration", "0.5", "--out", "k.csv", "-q",
                    "--controller", f"Bot.Cart.Link=/usr/bin/python3 peer.py {module_dir}"],
                   cwd=tmp_path, check=True)
    log = (tmp_path / "k.controller.log").read_text(encoding="utf-8")
    assert log == "version 3 t 0.0 bodies 4 values 13\nsubscribed ['Bot.Cart.Châssis'] 0\n", log
