"""How a script finds its tools and the package: cocopp.executable.find_cocopp against
scripts/lib/cocopp-bin.sh (the shell scripts' way) in each case of their order, and
scripts/lib/python-path.sh, after which python3 imports the checkout's package from anywhere."""
import os
import pathlib
import subprocess
import tempfile
import unittest

from cocopp import executable

SOURCE = pathlib.Path(__file__).resolve().parents[2]


def fake_cocopp(directory):
    path = pathlib.Path(directory) / "cocopp"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("#!/bin/sh\n")
    path.chmod(0o755)
    return path


def shell_finds(checkout, env):
    """What cocopp_executable prints for `checkout`, or None where it fails."""
    result = subprocess.run(
        ["bash", "-c", f'source {SOURCE}/scripts/lib/cocopp-bin.sh && cocopp_executable "$1"',
         "-", str(checkout)], env=env, capture_output=True, text=True)
    return pathlib.Path(result.stdout.strip()) if result.returncode == 0 else None


def python_finds(checkout, env):
    saved = dict(os.environ)
    os.environ.clear()
    os.environ.update(env)
    try:
        return executable.find_cocopp(checkout)
    except SystemExit as error:
        return str(error)
    finally:
        os.environ.clear()
        os.environ.update(saved)


class FindCocopp(unittest.TestCase):
    def setUp(self):
        self.scratch = tempfile.TemporaryDirectory()
        root = pathlib.Path(self.scratch.name)
        self.checkout, self.elsewhere = root / "checkout", root / "empty_checkout"
        self.elsewhere.mkdir()
        self.built = fake_cocopp(self.checkout / "build" / "bin")
        self.bin_dir = root / "bin_dir"
        self.on_path = fake_cocopp(root / "path")
        self.base = {"PATH": "/usr/bin:/bin", "HOME": str(root)}

    def tearDown(self):
        self.scratch.cleanup()

    def both(self, checkout, **env):
        env = dict(self.base, **env)
        return shell_finds(checkout, env), python_finds(checkout, env)

    def test_cocopp_bin_dir_first(self):
        shell, python = self.both(self.checkout, COCOPP_BIN_DIR=str(self.bin_dir))
        self.assertEqual(shell, self.bin_dir / "cocopp")
        self.assertEqual(python, shell)

    def test_then_the_checkouts_build(self):
        shell, python = self.both(self.checkout, PATH=f"{self.on_path.parent}:/usr/bin:/bin")
        self.assertEqual(shell, self.built)
        self.assertEqual(python, shell)

    def test_then_the_one_on_path(self):
        shell, python = self.both(self.elsewhere, PATH=f"{self.on_path.parent}:/usr/bin:/bin")
        self.assertEqual(shell, self.on_path)
        self.assertEqual(python, shell)

    def test_none_says_what_to_do(self):
        shell, python = self.both(self.elsewhere)
        self.assertIsNone(shell)
        self.assertIn("scripts/setup.sh", python)

    def test_this_checkouts_package_knows_its_checkout(self):
        self.assertEqual(executable.checkout_of_package(), SOURCE)


class PackageOnPythonPath(unittest.TestCase):
    def test_after_the_build_script_python3_imports_the_checkouts_package(self):
        with tempfile.TemporaryDirectory() as home:
            env = {"PATH": "/usr/bin:/bin", "HOME": home}
            said = subprocess.run(["bash", "-c", f"source {SOURCE}/scripts/lib/python-path.sh "
                                   f"&& put_package_on_python_path {SOURCE}"],
                                  env=env, capture_output=True, text=True, check=True).stdout
            self.assertIn(f"imports cocopp from {SOURCE}/python", said)
            imported = subprocess.run(["/usr/bin/python3", "-c",
                                       "import cocopp.case; print(cocopp.case.__file__)"],
                                      cwd=home, env=env, capture_output=True, text=True)
            self.assertEqual(imported.stdout.strip(), str(SOURCE / "python/cocopp/case.py"),
                             imported.stderr)

    def test_a_removed_checkout_falls_back_to_the_one_built_before(self):
        with tempfile.TemporaryDirectory() as home:
            env = {"PATH": "/usr/bin:/bin", "HOME": home}
            with tempfile.TemporaryDirectory() as clone:  # a CI clone, built last, then removed
                os.makedirs(os.path.join(clone, "python"))
                for checkout in (SOURCE, clone, clone):
                    subprocess.run(["bash", "-c", f"source {SOURCE}/scripts/lib/python-path.sh "
                                    f"&& put_package_on_python_path {checkout}"],
                                   env=env, capture_output=True, text=True, check=True)
                site = subprocess.run(["/usr/bin/python3", "-m", "site", "--user-site"],
                                      env=env, capture_output=True, text=True,
                                      check=True).stdout.strip()
                with open(os.path.join(site, "cocopp-checkout.pth")) as pth:
                    self.assertEqual(pth.read().split(), [os.path.join(clone, "python"),
                                                          str(SOURCE / "python")])
            imported = subprocess.run(["/usr/bin/python3", "-c",
                                       "import cocopp.case; print(cocopp.case.__file__)"],
                                      cwd=home, env=env, capture_output=True, text=True)
            self.assertEqual(imported.stdout.strip(), str(SOURCE / "python/cocopp/case.py"),
                             imported.stderr)

if __name__ == "__main__":
    unittest.main()
