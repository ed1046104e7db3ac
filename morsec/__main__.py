from morsec.cli import main

main()
