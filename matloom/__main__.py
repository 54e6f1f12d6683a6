from matloom.cli.main import main

main()
