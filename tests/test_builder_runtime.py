"""Every MORSE-style builder script of the corpus runs with `morsec run script.py` and answers pymorse:
its robots and components are discovered, its streams deliver, its services answer, it quits."""

from pathlib import Path

import pytest
from runtime_helpers import Morsec  # noqa: E402

from morsec.pymorse_compat import patch_pymorse  # noqa: E402

patch_pymorse()

from pymorse import Morse  # noqa: E402

SCRIPTS = Path(__file__).resolve().parent / "builder_scripts"
CORPUS = sorted(p.stem for p in SCRIPTS.glob("*.py"))


@pytest.mark.parametrize("name", CORPUS)
def test_corpus_script_answers_pymorse(name, tmp_path):
    script = tmp_path / f"{name}.py"  # run from a scratch folder: text streams write where morsec runs
    script.write_text((SCRIPTS / f"{name}.py").read_text())
    with Morsec(script, tmp_path, cwd=tmp_path, prebuild=False, strategy="fixed_step") as sim:
        with Morse(port=sim.service_port) as client:
            details = client.rpc("simulation", "details")
            robots = [r["name"] for r in details["robots"]]
            assert robots and sorted(robots) == sorted(client.rpc("simulation", "list_robots"))
            before = client.time()
            client.sleep(0.1)
            assert client.time() >= before + 0.1 - 1e-6
            streams = client.rpc("simulation", "get_all_stream_ports")
            for robot in details["robots"]:
                for fqn, component in robot["components"].items():
                    assert fqn.startswith(robot["name"] + ".")
                    if ["morsec.middleware.socket", "OUT"] in component.get("stream_interfaces", []):
                        assert fqn in streams
                        node = getattr(client, robot["name"].replace(".", "_"))
                        for part in fqn.split(".")[1:]:
                            node = getattr(node, part)  # attribute access lets pymorse connect the stream
                        message = node.get(timeout=20)
                        assert message is not None and "timestamp" in message
                        break  # one stream per robot is enough to show the wiring
            client.quit()
