"""The dense reward's ladder (v12): every rung from hovering to holding pays more than the one
below it, and the local optimum PPO and SAC found on v7 (the hand closed in the air above the
part) pays less than hovering with the fingers open."""

from gripper.envs.reference_policies import ladder_returns


def test_each_rung_pays_more_than_the_one_below():
    r = ladder_returns(episodes=4, seed=0, objects="block,cylinder", action_mode="synergy")
    ret = {k: v["return"] for k, v in r.items()}
    assert r["hold"]["success"] == 1.0 and r["touch"]["success"] == 0.0
    assert ret["hold"] > ret["touch"] > ret["hover_open"] > max(ret["idle"], ret["hover_closed"])
    # under v11 the closed hover paid more than the open one: the trap the ladder removes
    v11 = {k: v["return_v11"] for k, v in r.items()}
    assert v11["hover_closed"] > v11["idle"]
    assert ret["hover_closed"] < ret["hover_open"]
