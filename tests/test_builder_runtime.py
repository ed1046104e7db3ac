"""Every MORSE-style builder script of the corpus runs with `morsec run script.py` and answers pymorse:
its robots and components are discovered, its streams deliver, its services answer, it quits."""

import contextlib
import subprocess
from pathlib import Path

import pytest
from runtime_helpers import MORSEC, Morsec, start_all, stop_all  # noqa: E402

from morsec.pymorse_compat import patch_pymorse  # noqa: E402

patch_pymorse()

from pymorse import Morse  # noqa: E402

SCRIPTS = Path(__file__).resolve().parent / "builder_scripts"
CORPUS = sorted(p.stem for p in SCRIPTS.glob("*.py"))


# scripts whose robots are split over nodes (configure_multinode): this node, and the others run beside it
NODES = {"multinode": ("nodeA", "nodeB")}


@contextlib.contextmanager
def simulation(name: str, script: Path, tmp_path: Path):
    """`morsec run script.py`; for a multinode script, its first node, with the multinode server (on the
    script's default port) and the other nodes running."""
    if name not in NODES:
        with Morsec(script, tmp_path, cwd=tmp_path, prebuild=False, strategy="fixed_step") as sim:
            yield sim
        return
    server = subprocess.Popen([str(MORSEC), "multinode-server"], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              text=True, start_new_session=True)
    try:
        assert server.stdout.readline().startswith("MULTINODE SERVER")
        this, *others = NODES[name]
        sims = start_all(*(Morsec(script, tmp_path, cwd=tmp_path, prebuild=False, strategy="fixed_step",
                                  args=("--node", node)) for node in (this, *others)))
        try:
            yield sims[0]
        finally:
            stop_all(*sims)
    finally:
        server.terminate()
        server.wait(10)


@pytest.mark.parametrize("name", CORPUS)
def test_corpus_script_answers_pymorse(name, tmp_path):
    script = tmp_path / f"{name}.py"  # run from a scratch folder: text streams write where morsec runs
    script.write_text((SCRIPTS / f"{name}.py").read_text())
    with simulation(name, script, tmp_path) as sim:
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
